// --aovs end to end: the real geocold-cl writes <output>.aovs.exr, which OpenImageIO (an
// independent EXR reader, not our writer's code) opens as one part per layer with the
// documented names, channels and types; each layer's pixels are those of the same AOV rendered
// on its own (--aov NAME, read back from PFM), and sample-count is the spp.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>

#include "host/image/image_io.h"
#include "process.h"

#if defined(GC_HAVE_OIIO)
#include <OpenImageIO/imageio.h>
#endif

namespace gc::test {
namespace {

namespace fs = std::filesystem;

const fs::path k_cornell = fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";

RunResult run(const std::vector<std::string>& extra)
{
    std::vector<std::string> args = {k_cornell.string(), "--quiet", "--device", "cpu", "--res", "24x16",
                                     "--max-depth", "4"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_process(cli_path(), args, cli_options());
    std::string what = "geocold-cl";
    for (const std::string& a : args) what += " " + a;
    std::printf("  %s -> %s (%.2f s)\n%s", what.c_str(), r.describe().c_str(), r.seconds, r.err.c_str());
    return r;
}

TEST(AovLayersCli, EveryLayerIsAPartOfOneExrWithTheValuesOfItsOwnRender)
{
#if !defined(GC_HAVE_OIIO)
    GTEST_SKIP() << "built without OpenImageIO: no independent EXR reader";
#else
    if (!have_cpu_device()) GTEST_SKIP() << "no CPU OpenCL device";
    const TempDir dir;
    const RunResult r = run({"--spp", "8", "--aovs", "albedo,normal,depth,primid,variance,sample-count", "-o",
                             (dir / "beauty.pfm").string()});
    ASSERT_EQ(r.exit_code, 0);
    const fs::path layers = dir / "beauty.aovs.exr";
    ASSERT_TRUE(fs::is_regular_file(layers));

    struct Expected {
        const char* part;
        std::vector<std::string> channels;
        OIIO::TypeDesc type;
        const char* aov;  // the --aov whose own render it must equal, or null
        const char* spp;
    };
    const std::vector<Expected> expected = {
        {"albedo", {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, "albedo", "16"},
        {"normal", {"X", "Y", "Z"}, OIIO::TypeDesc::FLOAT, "normal", "16"},
        {"depth", {"Z"}, OIIO::TypeDesc::FLOAT, "depth", "1"},
        {"primid", {"id"}, OIIO::TypeDesc::UINT32, "primid", "1"},
        {"variance", {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, nullptr, nullptr},
        {"sample-count", {"N"}, OIIO::TypeDesc::UINT32, nullptr, nullptr},
    };
    auto in = OIIO::ImageInput::open(layers.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const std::size_t pixels = 24 * 16;
    for (std::size_t p = 0; p < expected.size(); ++p) {
        const Expected& e = expected[p];
        ASSERT_TRUE(in->seek_subimage(int(p), 0)) << "no part " << p;
        const OIIO::ImageSpec& spec = in->spec();
        const std::string name = spec.get_string_attribute("oiio:subimagename");
        std::printf("  part %zu '%s': %dx%d, channels", p, name.c_str(), spec.width, spec.height);
        for (const std::string& c : spec.channelnames) std::printf(" %s", c.c_str());
        std::printf("\n");
        EXPECT_EQ(name, e.part);
        EXPECT_EQ(spec.width, 24);
        EXPECT_EQ(spec.height, 16);
        EXPECT_EQ(spec.channelnames, e.channels);
        EXPECT_EQ(spec.format, e.type) << e.part;
        const int n = spec.nchannels;
        std::vector<float> f(pixels * n);
        std::vector<std::uint32_t> u(pixels * n);
        if (e.type == OIIO::TypeDesc::FLOAT) ASSERT_TRUE(in->read_image(int(p), 0, 0, n, OIIO::TypeDesc::FLOAT, f.data()));
        else ASSERT_TRUE(in->read_image(int(p), 0, 0, n, OIIO::TypeDesc::UINT32, u.data()));

        if (e.aov) {
            // OpenImageIO lists R, G, B in that order (the file stores channels sorted by name).
            const fs::path own = dir / (std::string(e.aov) + ".pfm");
            ASSERT_EQ(run({"--aov", e.aov, "--spp", e.spp, "-o", own.string()}).exit_code, 0);
            const Film film = read_image(own);
            std::size_t differ = 0;
            for (std::size_t i = 0; i < pixels; ++i) {
                const float* rgb = film.data().data() + 4 * i;
                for (int c = 0; c < n; ++c) {
                    const int k = c;
                    if (e.type == OIIO::TypeDesc::UINT32) {
                        const std::uint32_t want = rgb[k] < 0 ? 0xffffffffu : std::uint32_t(rgb[k]);
                        differ += u[i * n + c] != want;
                    } else {
                        differ += std::memcmp(&f[i * n + c], &rgb[k], 4) != 0;
                    }
                }
            }
            const std::size_t centre = 8 * 24 + 12;
            std::printf("  %s: %zu of %zu values differ from --aov %s --spp %s; centre pixel %g\n", e.part, differ,
                        pixels * n, e.aov, e.spp, e.type == OIIO::TypeDesc::UINT32 ? double(u[centre]) : double(f[centre * n]));
            EXPECT_EQ(differ, 0u) << e.part;
        } else if (e.type == OIIO::TypeDesc::UINT32) {
            std::size_t not_spp = 0;
            for (std::uint32_t v : u) not_spp += v != 8;
            std::printf("  sample-count: %zu of %zu pixels not 8\n", not_spp, pixels);
            EXPECT_EQ(not_spp, 0u);
        } else {
            double sum = 0;
            std::size_t bad = 0;
            for (float v : f) {
                bad += !(std::isfinite(v) && v >= 0.0f);
                sum += v;
            }
            std::printf("  variance: mean %g, %zu values negative or not finite\n", sum / f.size(), bad);
            EXPECT_EQ(bad, 0u);
            EXPECT_GT(sum, 0.0);  // 8 samples of a path-traced Cornell box are noisy
        }
    }
    EXPECT_FALSE(in->seek_subimage(int(expected.size()), 0)) << "more parts than layers";
    in->close();
#endif
}

TEST(AovLayersCli, BadListsAreRefusedBeforeRendering)
{
    const TempDir dir;
    const std::string out = (dir / "x.pfm").string();
    RunResult r = run({"--aovs", "albedo,colour", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--aovs: unknown layer 'colour'"), std::string::npos) << r.err;
    r = run({"--aovs", "depth,depth", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("named twice"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace gc::test
