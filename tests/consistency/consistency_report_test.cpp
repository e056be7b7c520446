// The consistency report on hand-made images (no device): every pair compared, the text and
// JSON forms, and the --consistency options. The figures and verdicts themselves are
// tests/image/compare_test.cpp's.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/app/consistency_report.h"
#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {
namespace {

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
        r.image = Film(16, 16);
        r.image.fill(Rgba{0.5f, 0.25f, 0.1f, 1.0f});
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
    EXPECT_DOUBLE_EQ(run.pairs[0].diff.mean_test, 2.0 * run.pairs[0].diff.mean_ref);  // b measured against a
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
