// The command line against a hostile user: bad options, bad output paths, a full disk.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "host/image/image_io.h"
#include "process.h"

namespace gc::test {
namespace {

const std::filesystem::path k_cornell = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";

void show(const char* what, const RunResult& r)
{
    std::string shown = r.err;
    while (!shown.empty() && shown.back() == '\n') shown.pop_back();
    std::printf("  %s -> %s (%.2f s)\n    %s\n", what, r.describe().c_str(), r.seconds, shown.c_str());
}

struct BadArgs {
    std::vector<std::string> args;
    std::string message;
};

TEST(Cli, BadOptionsAreUsageErrors)
{
    const std::string scene = k_cornell.string();
    const std::vector<BadArgs> cases = {
        {{scene, "--frobnicate"}, "unknown option '--frobnicate'"},
        {{scene, "--spp", "0"}, "--spp expects an integer in [1, 16777216], got '0'"},
        {{scene, "--spp", "-3"}, "--spp expects an integer in [1, 16777216], got '-3'"},
        {{scene, "--spp", "99999999999999999999999"}, "--spp expects an integer"},
        {{scene, "--spp=1e3"}, "--spp expects an integer"},
        {{scene, "--res", "0x0"}, "--res expects an integer in [1, 16384], got '0'"},
        {{scene, "--res", "100000x1"}, "--res expects an integer in [1, 16384], got '100000'"},
        {{scene, "--res", "512"}, "--res expects WIDTHxHEIGHT"},
        {{scene, "--width", "-1"}, "--width expects an integer"},
        {{scene, "--max-depth", "0"}, "--max-depth expects an integer in [1, 1024]"},
        {{scene, "--fov", "180"}, "--fov expects a vertical field of view in (0, 180) degrees"},
        {{scene, "--env", "1,nan,1"}, "--env expects a finite number"},
        {{scene, "--time-limit", "-1"}, "--time-limit expects a positive number of seconds"},
        {{scene, "--wavefront-size", "1"}, "--wavefront-size expects an integer in [1024,"},
        {{scene, "--samples-per-pass", "0"}, "--samples-per-pass expects an integer in [1,"},
        {{scene, "--up", "0,0,0"}, "--up must not be the zero vector"},
        {{scene, "--spp"}, "--spp needs a value"},
        {{scene, scene}, "more than one scene given"},
        {{}, "no scene given"},
    };
    for (const BadArgs& c : cases) {
        const RunResult r = run_process(cli_path(), c.args, cli_options());
        std::string what = "geocold-cl";
        for (const std::string& a : c.args) what += " " + (a == scene ? std::string("SCENE") : a);
        show(what.c_str(), r);
        EXPECT_EQ(r.signal, 0) << what;
        EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << r.err;
        EXPECT_NE(r.err.find("Try 'geocold-cl --help'"), std::string::npos) << r.err;
        EXPECT_LT(r.seconds, 10.0) << "a usage error must not touch devices or scenes";
    }
}

TEST(Cli, HelpDocumentsExitCodes)
{
    const RunResult r = run_process(cli_path(), {"--help"}, cli_options());
    EXPECT_EQ(r.exit_code, 0);
    for (const char* line : {"2 bad command line", "3 unreadable or malformed input file", "4 no usable device",
                             "5 output could not be written", "130 interrupted (partial image written)"})
        EXPECT_NE(r.out.find(line), std::string::npos) << line;
}

TEST(Cli, MissingOutputFolderFailsBeforeLoadingOrRendering)
{
    const TempDir dir;
    const std::string output = (dir / "no/such/folder/out.png").string();
    // Hours of work requested: only an early check can make this fast. The scene does not even
    // exist: the output is checked first, so the answer is about the output (exit 5).
    for (const std::string& scene : {k_cornell.string(), (dir / "missing.obj").string()}) {
        const RunResult r = run_process(cli_path(), {scene, "--spp", "1000000", "--res", "4096x4096", "-o", output},
                                        cli_options());
        show("-o no/such/folder/out.png", r);
        EXPECT_EQ(r.exit_code, 5) << r.err;
        EXPECT_NE(r.err.find(output), std::string::npos) << r.err;
        EXPECT_EQ(r.count_err_lines("error:"), 1) << r.err;
        EXPECT_LT(r.seconds, 5.0);
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(Cli, OutputPathIsAFolder)
{
    const TempDir dir;
    std::filesystem::create_directories(dir / "image.png");
    const RunResult r = run_process(cli_path(), {k_cornell.string(), "--spp", "1000000", "-o", (dir / "image.png").string()},
                                    cli_options());
    show("-o <a folder>", r);
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find("image.png"), std::string::npos) << r.err;
    EXPECT_LT(r.seconds, 5.0);
    EXPECT_TRUE(std::filesystem::is_directory(dir / "image.png"));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"image.png"});
}

TEST(Cli, UnsupportedOutputFormatLeavesExistingFileAlone)
{
    const TempDir dir;
    const std::filesystem::path target = dir / "image.xyz";
    write_file(target, "precious previous contents\n");
    const RunResult r = run_process(cli_path(), {k_cornell.string(), "--spp", "1000000", "-o", target.string()}, cli_options());
    show("-o image.xyz", r);
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find("image.xyz"), std::string::npos) << r.err;
    EXPECT_LT(r.seconds, 5.0);
    EXPECT_EQ(read_file(target), "precious previous contents\n");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"image.xyz"});
}

// An environment variable with a value the renderer does not know is a usage error (exit 2)
// that names the variable and the value, before anything is written.
void expect_env_usage_error(const char* name, const char* value, const std::string& message)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    RunOptions options = cli_options();
    options.env[name] = value;
    const RunResult r = run_process(
        cli_path(), {k_cornell.string(), "--spp", "1", "--res", "8x8", "--device", "cpu", "-o", (dir / "out.ppm").string()},
        options);
    show((std::string(name) + "=" + value).c_str(), r);
    EXPECT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty()) << "an image was written";
}

TEST(Cli, BadPathKernelVariableIsAUsageError)
{
    expect_env_usage_error("GEOCOLD_PATH_KERNEL", "mega", "GEOCOLD_PATH_KERNEL must be 'wavefront' or 'megakernel', not 'mega'");
}

TEST(Cli, BadBvhWidthVariableIsAUsageError)
{
    expect_env_usage_error("GEOCOLD_BVH_WIDTH", "3", "GEOCOLD_BVH_WIDTH must be 2, 4 or 8, not '3'");
}

TEST(Cli, BadKernelFeaturesVariableIsAUsageError)
{
    expect_env_usage_error("GEOCOLD_KERNEL_FEATURES", "none", "GEOCOLD_KERNEL_FEATURES must be 'scene' or 'all', not 'none'");
}

// The CU count in the CPU row of --list-devices, read under the table's "CUs" header (the
// column is right-aligned and ends where the header does); -1 if there is no CPU row.
int cpu_compute_units(const std::string& table)
{
    std::istringstream lines(table);
    std::string line;
    std::size_t end = std::string::npos;
    while (std::getline(lines, line)) {
        if (end == std::string::npos) {
            const std::size_t at = line.find(" CUs ");
            if (at != std::string::npos) end = at + 4;
            continue;
        }
        if (line.find(" cpu ") == std::string::npos || line.size() < end) continue;
        return std::atoi(line.substr(end - 4, 4).c_str());
    }
    return -1;
}

// --threads caps PoCL's CPU workers: the CPU device then reports that many compute units.
TEST(Cli, ThreadsCapsTheCpuDevice)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const RunResult all = run_process(cli_path(), {"--list-devices"}, cli_options());
    ASSERT_EQ(all.exit_code, 0) << all.err;
    const int cores = cpu_compute_units(all.out);
    std::printf("  --list-devices: CPU device with %d compute units\n", cores);
    if (cores < 2) GTEST_SKIP() << "one core: nothing to cap";
    const RunResult one = run_process(cli_path(), {"--threads", "1", "--list-devices"}, cli_options());
    ASSERT_EQ(one.exit_code, 0) << one.err;
    std::printf("  --threads 1 --list-devices: %d compute units\n", cpu_compute_units(one.out));
    EXPECT_EQ(cpu_compute_units(one.out), 1) << one.out;

    // And a render under the cap still works.
    const TempDir dir;
    const RunResult r = run_process(cli_path(), {k_cornell.string(), "--threads", "1", "--spp", "1", "--res", "16x16",
                                                 "--device", "cpu", "-o", (dir / "one.pfm").string()},
                                    cli_options());
    show("--threads 1 render", r);
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

// --time-limit ends a render that asked for far more samples than fit, with the image of the
// samples done. 10^6 spp of a 64x64 Cornell box would take minutes on the slowest device
// here; the bound of 30 s is loose so that a loaded machine cannot fail it, and still far
// below what ignoring the limit costs.
TEST(Cli, TimeLimitEndsTheRenderWithTheSamplesDone)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const RunResult r =
        run_process(cli_path(), {k_cornell.string(), "--spp", "1000000", "--res", "64x64", "--time-limit", "1",
                                 "--device", "cpu", "-o", (dir / "limited.pfm").string()},
                    cli_options());
    show("--spp 1000000 --time-limit 1", r);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_LT(r.seconds, 30.0);
    EXPECT_TRUE(std::filesystem::exists(dir / "limited.pfm"));
    // "wrote ... (64x64, N spp, ...)": some samples, not all of them.
    const std::size_t at = r.err.find("64x64, ");
    ASSERT_NE(at, std::string::npos) << r.err;
    const unsigned long spp = std::strtoul(r.err.c_str() + at + 7, nullptr, 10);
    std::printf("  rendered %lu of 1000000 spp\n", spp);
    EXPECT_GT(spp, 0ul);
    EXPECT_LT(spp, 1000000ul);
}

// A glTF model shipped without lights (the usual case) under the default black environment
// renders black: the user hears so before the render, with the way out, and the render still
// runs (exit 0). A lit scene and an --env say nothing.
TEST(Cli, UnlitSceneIsWarnedAboutBeforeRendering)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const std::string box = (std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes/box-textured/BoxTextured.gltf").string();
    const std::vector<std::string> small = {"--spp", "1", "--res", "16x16", "--device", "cpu", "-o", (dir / "out.pfm").string()};
    struct Case {
        std::string what;
        std::vector<std::string> args;
        bool warned;
    };
    const std::vector<Case> cases = {
        {"BoxTextured.gltf", {box}, true},
        {"BoxTextured.gltf --integrator whitted", {box, "--integrator", "whitted"}, true},
        {"BoxTextured.gltf --env 1,1,1", {box, "--env", "1,1,1"}, false},
        {"BoxTextured.gltf --aov albedo", {box, "--aov", "albedo"}, false},
        {"CornellBox-Original.obj", {k_cornell.string()}, false},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = c.args;
        args.insert(args.end(), small.begin(), small.end());
        const RunResult r = run_process(cli_path(), args, cli_options());
        show(c.what.c_str(), r);
        EXPECT_EQ(r.exit_code, 0) << c.what << "\n" << r.err;
        const bool warned = r.err.find("nothing lights this scene") != std::string::npos;
        EXPECT_EQ(warned, c.warned) << c.what << "\n" << r.err;
        if (c.warned) {
            EXPECT_NE(r.err.find("BoxTextured.gltf: nothing lights"), std::string::npos) << r.err;
        }
    }
}

// A full disk, simulated with RLIMIT_FSIZE (writes past the limit fail with EFBIG): the
// write fails after the render, and the previous image must survive byte for byte.
TEST(Cli, FullDiskKeepsThePreviousImage)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const std::vector<std::string> render = {k_cornell.string(), "--spp", "1", "--res", "32x32", "--device", "cpu"};
    // Warm-up with the same settings, so neither our kernel cache nor the driver's needs to
    // write a file while the limit is on (that would fail for the wrong reason).
    std::vector<std::string> args = render;
    args.insert(args.end(), {"-o", (dir / "warmup.pfm").string()});
    const RunResult warm = run_process(cli_path(), args, cli_options());
    ASSERT_EQ(warm.exit_code, 0) << warm.err;
    std::filesystem::remove(dir / "warmup.pfm");

    const std::filesystem::path target = dir / "image.pfm";
    const std::string previous = "PF\n1 1\n-1.0\n" + std::string(12, '\x01');
    write_file(target, previous);
    RunOptions options = cli_options();
    options.max_file_size = 1024;  // a 32x32 PFM is 12 KiB
    args = render;
    args.insert(args.end(), {"-o", target.string()});
    const RunResult r = run_process(cli_path(), args, options);
    show("full disk (RLIMIT_FSIZE 1 KiB) -o image.pfm", r);
    EXPECT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find(target.string()), std::string::npos) << r.err;
    EXPECT_EQ(r.count_err_lines("error:"), 1) << r.err;
    EXPECT_EQ(read_file(target), previous) << "the previous image was damaged";
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"image.pfm"}) << "temp files left behind";
}

// Khronos' TextureTransformTest through the CLI, as its README describes it: the top row's
// offsets read the U (green), V (blue) and UV (cyan) quadrants of UV.png, not the olive "not
// supported" one; the rotated arrow (22.5 degrees, bottom left) points towards the "correct"
// marker. The camera looks down -z at the quads' plane (z = 0), so a point (x, y) on it lands
// at pixel ((x / h + 1) * 128, (1 - y / h) * 128) of the 256 x 256 image, h = 4 tan(30 deg).
TEST(Cli, TextureTransformSampleRendersAsItsReadmeSays)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const std::filesystem::path scene =
        std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes/texture-transform/TextureTransformTest.gltf";
    const std::filesystem::path out = dir / "albedo.pfm";
    const RunResult r = run_process(cli_path(),
                                    {scene.string(), "--aov", "albedo", "--spp", "1", "--res", "256x256", "--device", "cpu",
                                     "--look-from", "0,0,4", "--look-at", "0,0,0", "--up", "0,1,0", "--fov", "60", "-o",
                                     out.string()},
                                    cli_options());
    show("TextureTransformTest", r);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("KHR_texture_transform"), std::string::npos) << "a supported extension: no warning";
    const Film film = read_image(out);
    ASSERT_EQ(film.width(), 256u);
    const double h = 4.0 * std::tan(30.0 * 3.14159265358979 / 180.0);
    auto at = [&](double x, double y) {
        const auto px = static_cast<std::uint32_t>((x / h + 1.0) * 128.0);
        const auto py = static_cast<std::uint32_t>((1.0 - y / h) * 128.0);
        return film.at(px, py);
    };
    // Quad-local (-0.4, 0.4): uv (0.05, 0.05) before the offset, a flat corner of a quadrant.
    const Rgba offset_u = at(-1.1 - 0.4, 0.55 + 0.4), offset_v = at(0.0 - 0.4, 0.55 + 0.4), offset_uv = at(1.1 - 0.4, 0.55 + 0.4);
    std::printf("  offset U (%.3f %.3f %.3f)  V (%.3f %.3f %.3f)  UV (%.3f %.3f %.3f)\n", offset_u.r, offset_u.g, offset_u.b,
                offset_v.r, offset_v.g, offset_v.b, offset_uv.r, offset_uv.g, offset_uv.b);
    EXPECT_TRUE(offset_u.g > 0.3f && offset_u.r < 0.05f && offset_u.b < 0.05f) << "green";
    EXPECT_TRUE(offset_v.b > 0.3f && offset_v.r < 0.05f && offset_v.g < 0.05f) << "blue";
    EXPECT_TRUE(offset_uv.g > 0.3f && offset_uv.b > 0.3f && offset_uv.r < 0.05f) << "cyan";
    // The rotation quad (centre (-1.1, -0.55)): the arrow's shaft at texel uv (0.45, 0.45) is
    // drawn where the mesh uv is R^-1 (0.45, 0.45) = (0.243, 0.588), i.e. quad-local
    // (-0.257, -0.088); the unrotated shaft's spot, quad-local (-0.05, 0.05), is now white.
    const Rgba shaft = at(-1.1 - 0.257, -0.55 - 0.088), unrotated = at(-1.1 - 0.05, -0.55 + 0.05);
    std::printf("  rotated shaft %.3f, unrotated shaft's spot %.3f\n", shaft.r, unrotated.r);
    EXPECT_LT(shaft.r, 0.1f);
    EXPECT_GT(unrotated.r, 0.5f);
}

// The same sample, path traced: it draws three of its meshes twice, so geocold-cl keeps them
// as instances (-v says so; its AOV layers trace them too), and the image is the flattened
// scene's (--flatten-instances) up to the rounding of the instances' attributes. Metric: the
// largest absolute difference of a pixel channel of the two PFMs, printed, bound 1e-3 (5.4e-6
// when this was written).
TEST(Cli, ReusedMeshesAreInstancedAndRenderAsFlattened)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const std::string scene =
        (std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes/texture-transform/TextureTransformTest.gltf").string();
    const std::vector<std::string> common = {scene, "--spp", "4", "--res", "64x48", "--device", "cpu", "--env", "1,1,1"};
    std::vector<std::string> instanced_args = common, flat_args = common;
    // The AOV layers of an instanced frame trace its instances as the beauty does.
    instanced_args.insert(instanced_args.end(), {"-v", "--aovs", "albedo,depth", "-o", (dir / "instanced.pfm").string()});
    flat_args.insert(flat_args.end(), {"--flatten-instances", "-v", "-o", (dir / "flat.pfm").string()});
    const RunResult instanced = run_process(cli_path(), instanced_args, cli_options());
    const RunResult flat = run_process(cli_path(), flat_args, cli_options());
    ASSERT_EQ(instanced.exit_code, 0) << instanced.err;
    ASSERT_EQ(flat.exit_code, 0) << flat.err;
    EXPECT_NE(instanced.err.find("instanced: 9 meshes drawn by 12 instances"), std::string::npos) << instanced.err;
    EXPECT_EQ(flat.err.find("instanced:"), std::string::npos) << flat.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "instanced.aovs.exr")) << instanced.err;
    const Film a = read_image(dir / "instanced.pfm"), b = read_image(dir / "flat.pfm");
    ASSERT_EQ(a.width(), b.width());
    float worst = 0.0f;
    double mean = 0.0;
    for (std::uint32_t y = 0; y < a.height(); ++y)
        for (std::uint32_t x = 0; x < a.width(); ++x) {
            const Rgba p = a.at(x, y), q = b.at(x, y);
            worst = std::max({worst, std::fabs(p.r - q.r), std::fabs(p.g - q.g), std::fabs(p.b - q.b)});
            mean += p.g;
        }
    std::printf("  instanced vs flattened: max |difference| %g (bound 1e-3), mean green %.4f\n", double(worst),
                mean / (double(a.width()) * a.height()));
    EXPECT_LE(worst, 1e-3f);
    EXPECT_GT(mean, 0.0);
}

}  // namespace
}  // namespace gc::test
