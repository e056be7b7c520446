// The consistency figures and verdicts on hand-made images (no device), and the
// --consistency options.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "host/app/consistency_report.h"
#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {
namespace {

// A smooth, non-black test image.
Film gradient(std::uint32_t w, std::uint32_t h)
{
    Film f(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x)
            f.set(x, y, Rgba{0.1f + 0.8f * float(x) / float(w), 0.5f, 0.2f + 0.3f * float(y) / float(h), 1.0f});
    return f;
}

TEST(ConsistencyReport, IdenticalImagesPass)
{
    const Film a = gradient(32, 32);
    const ConsistencyPair p = compare_renders(a, a);
    std::printf("identical: rel_mse %g within %g identical %zu/%zu\n", p.rel_mse, p.within, p.identical, p.pixels);
    EXPECT_TRUE(p.passed) << p.why;
    EXPECT_EQ(p.rel_mse, 0.0);
    EXPECT_EQ(p.max_abs, 0.0);
    EXPECT_EQ(p.within, 1.0);
    EXPECT_EQ(p.identical, a.pixel_count());
    EXPECT_GT(p.mean_a, 0.0);
}

TEST(ConsistencyReport, WithinToleranceIsRelativeAndSymmetric)
{
    Film a(2, 1), b(2, 1);
    // Pixel 0: off by 0.9e-3 relative to the larger value: within. Pixel 1: 1.1e-3: outside.
    a.set(0, 0, Rgba{1.0f, 1.0f, 1.0f, 1.0f});
    b.set(0, 0, Rgba{1.0f, 1.0f, 0.9991f, 1.0f});
    a.set(1, 0, Rgba{1.0f, 1.0f, 1.0f, 1.0f});
    b.set(1, 0, Rgba{1.0f, 0.9989f, 1.0f, 1.0f});
    const ConsistencyPair ab = compare_renders(a, b);
    const ConsistencyPair ba = compare_renders(b, a);
    std::printf("within %g / %g, identical %zu\n", ab.within, ba.within, ab.identical);
    EXPECT_EQ(ab.within, 0.5);
    EXPECT_EQ(ba.within, 0.5);
    EXPECT_EQ(ab.identical, 0u);
    EXPECT_NEAR(ab.max_abs, 0.0011, 1e-6);
}

TEST(ConsistencyReport, BlackPixelsUseTheAbsoluteFloor)
{
    Film a(2, 1), b(2, 1);
    a.set(0, 0, Rgba{0.0f, 0.0f, 0.0f, 1.0f});
    b.set(0, 0, Rgba{5e-7f, 0.0f, 0.0f, 1.0f});  // below the 1e-6 floor
    a.set(1, 0, Rgba{0.0f, 0.0f, 0.0f, 1.0f});
    b.set(1, 0, Rgba{2e-6f, 0.0f, 0.0f, 1.0f});  // above it
    EXPECT_EQ(compare_renders(a, b).within, 0.5);
}

// One decorrelated path in a 64-spp pixel: the pixel moves by sample / 64, far outside 1e-3
// relative, but the image's relative MSE stays small. The two limits judge the two effects.
TEST(ConsistencyReport, RareOutlierPixelsAreJudgedByFractionAndRelMse)
{
    const Film a = gradient(100, 100);
    Film b = a;
    Rgba c = b.at(7, 7);
    c.g += 1.0f / 64.0f;
    b.set(7, 7, c);
    const ConsistencyPair one = compare_renders(a, b);
    std::printf("one outlier of 10000: within %.4f%% rel_mse %.3g max_abs %.3g\n", 100 * one.within, one.rel_mse,
                one.max_abs);
    EXPECT_TRUE(one.passed) << one.why;
    EXPECT_DOUBLE_EQ(one.within, 0.9999);
    EXPECT_LT(one.rel_mse, 1e-5);

    // 20 such pixels (0.2 %): the fraction limit (99.9 %) fails.
    for (std::uint32_t i = 0; i < 20; ++i) {
        Rgba d = b.at(i, 50);
        d.r += 1.0f / 64.0f;
        b.set(i, 50, d);
    }
    const ConsistencyPair many = compare_renders(a, b);
    std::printf("21 outliers: within %.4f%% -> %s\n", 100 * many.within, many.why.c_str());
    EXPECT_FALSE(many.passed);
    EXPECT_NE(many.why.find("within tolerance"), std::string::npos);
}

TEST(ConsistencyReport, LargeRelMseFails)
{
    const Film a = gradient(16, 16);
    Film b = a;
    for (float& v : b.data()) v *= 1.01f;  // 1 % everywhere: rel MSE about 2e-5 .. 1e-4
    const ConsistencyPair p = compare_renders(a, b, ConsistencyTolerances{1e-5, 0.0, 1e-3, 1e-6});
    std::printf("1%% brighter: rel_mse %.3g -> %s\n", p.rel_mse, p.why.c_str());
    EXPECT_FALSE(p.passed);
    EXPECT_NE(p.why.find("rel MSE"), std::string::npos);
}

TEST(ConsistencyReport, BlackAndNonFiniteImagesFail)
{
    const Film black(8, 8);
    const ConsistencyPair p = compare_renders(black, black);
    EXPECT_FALSE(p.passed);
    EXPECT_NE(p.why.find("black"), std::string::npos);

    const Film a = gradient(8, 8);
    Film b = a;
    b.set(3, 3, Rgba{std::numeric_limits<float>::quiet_NaN(), 0, 0, 1});
    const ConsistencyPair q = compare_renders(a, b);
    EXPECT_FALSE(q.passed);
    EXPECT_EQ(q.nonfinite, 1u);
    EXPECT_LT(q.within, 1.0);
}

TEST(ConsistencyReport, SizeMismatchIsAnInputError)
{
    EXPECT_THROW(compare_renders(Film(4, 4), Film(4, 5)), InputError);
}

ConsistencyRun make_run(std::size_t devices)
{
    ConsistencyRun run;
    run.scene = "scenes/cornell-box/CornellBox-Original.obj";
    run.integrator = "path";
    run.width = run.height = 16;
    run.spp = 64;
    for (std::size_t i = 0; i < devices; ++i) {
        ConsistencyRender r;
        r.api = "opencl";
        r.device = "dev \"" + std::to_string(i) + "\"";
        r.platform = "PoCL\\test";
        r.seconds = 1.5;
        r.image = gradient(16, 16);
        run.renders.push_back(r);
    }
    run.pairs = compare_all(run.renders, run.tolerances);
    return run;
}

TEST(ConsistencyReport, EveryPairIsCompared)
{
    const ConsistencyRun run = make_run(3);
    ASSERT_EQ(run.pairs.size(), 3u);
    EXPECT_EQ(run.pairs[0].a, 0u);
    EXPECT_EQ(run.pairs[0].b, 1u);
    EXPECT_EQ(run.pairs[2].a, 1u);
    EXPECT_EQ(run.pairs[2].b, 2u);
    EXPECT_TRUE(run.passed());
    EXPECT_EQ(heatmap_stem(run, run.pairs[2]), "CornellBox-Original_1-vs-2");
}

TEST(ConsistencyReport, TextReportVerdicts)
{
    ConsistencyRun run = make_run(2);
    const std::string ok = format_report(run);
    std::fputs(ok.c_str(), stdout);
    EXPECT_NE(ok.find("0 vs 1"), std::string::npos);
    EXPECT_NE(ok.find("consistency: PASSED (1 pair)"), std::string::npos);

    for (float& v : run.renders[1].image.data()) v *= 2.0f;
    run.pairs = compare_all(run.renders, run.tolerances);
    const std::string bad = format_report(run);
    EXPECT_FALSE(run.passed());
    EXPECT_NE(bad.find("FAIL: "), std::string::npos);
    EXPECT_NE(bad.find("consistency: FAILED (1 of 1 pairs)"), std::string::npos);

    const ConsistencyRun one = make_run(1);
    EXPECT_TRUE(one.skipped());
    EXPECT_NE(format_report(one).find("consistency: SKIPPED"), std::string::npos);
}

TEST(ConsistencyReport, JsonHasTheFiguresAndEscapes)
{
    const std::string json = format_json(make_run(2));
    std::fputs(json.c_str(), stdout);
    for (const char* key : {"\"scene\"", "\"spp\": 64", "\"tolerances\"", "\"devices\"", "\"pairs\"", "\"rel_mse\"",
                            "\"max_abs\"", "\"within\"", "\"passed\": true", "\"skipped\": false"})
        EXPECT_NE(json.find(key), std::string::npos) << key;
    EXPECT_NE(json.find(R"("dev \"0\"")"), std::string::npos);
    EXPECT_NE(json.find(R"("PoCL\\test")"), std::string::npos);
    // Balanced braces and brackets (a cheap well-formedness check; no JSON parser is linked).
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < json.size(); ++i) {
        if (in_string) {
            if (json[i] == '\\') ++i;
            else if (json[i] == '"') in_string = false;
            continue;
        }
        if (json[i] == '"') in_string = true;
        else if (json[i] == '{' || json[i] == '[') ++depth;
        else if (json[i] == '}' || json[i] == ']') --depth;
        EXPECT_GE(depth, 0);
    }
    EXPECT_EQ(depth, 0);
    EXPECT_FALSE(in_string);
}

TEST(ConsistencyOptions, ParseAndDefaults)
{
    const Options o = parse_options({"--consistency", "--json", "out.json", "--heatmap", "maps", "scene.obj"});
    EXPECT_TRUE(o.consistency);
    EXPECT_EQ(o.json_path, "out.json");
    EXPECT_EQ(o.heatmap_dir, "maps");
    EXPECT_FALSE(o.res_given);
    EXPECT_FALSE(o.spp_given);
    EXPECT_TRUE(parse_options({"--consistency", "--res", "64x64", "s.obj"}).res_given);
    EXPECT_TRUE(parse_options({"--consistency", "--width", "64", "s.obj"}).res_given);
    EXPECT_THROW(parse_options({"--json", "out.json", "scene.obj"}), UsageError);
    EXPECT_THROW(parse_options({"--heatmap", "d", "scene.obj"}), UsageError);
    EXPECT_THROW(parse_options({"--consistency", "--json"}), UsageError);
}

}  // namespace
}  // namespace gc
