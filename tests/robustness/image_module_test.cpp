// The OpenImageIO image module (geocold-image-oiio.so) is dlopen()ed on first use: runs that
// need no image from it must work without it, and a missing or broken module must fail with
// the module's path and the loader's reason, exit 5, and no file written.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "process.h"

namespace gc::test {
namespace {

const std::filesystem::path k_cornell = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";
const std::vector<std::string> k_render = {k_cornell.string(), "--spp", "1", "--res", "8x8", "--device", "cpu"};

void show(const char* what, const RunResult& r)
{
    std::string shown = r.err;
    while (!shown.empty() && shown.back() == '\n') shown.pop_back();
    std::printf("  %s -> %s (%.2f s)\n    %s\n", what, r.describe().c_str(), r.seconds, shown.c_str());
}

RunOptions with_module(const std::filesystem::path& module)
{
    RunOptions options = cli_options();
    options.env["GEOCOLD_IMAGE_MODULE"] = module.string();
    return options;
}

RunResult render_to(const std::filesystem::path& output, const RunOptions& options)
{
    std::vector<std::string> args = k_render;
    args.insert(args.end(), {"-o", output.string()});
    return run_process(cli_path(), args, options);
}

TEST(ImageModule, HelpAndVersionNeedNoModule)
{
    const TempDir dir;
    const RunOptions options = with_module(dir / "missing.so");
    const RunResult help = run_process(cli_path(), {"--help"}, options);
    EXPECT_EQ(help.exit_code, 0) << help.err;
    EXPECT_NE(help.out.find("GEOCOLD_IMAGE_MODULE"), std::string::npos) << "--help must document the variable";
    EXPECT_TRUE(help.err.empty()) << help.err;
    const RunResult version = run_process(cli_path(), {"--version"}, options);
    EXPECT_EQ(version.exit_code, 0) << version.err;
    EXPECT_NE(version.out.find("geocold-cl"), std::string::npos) << version.out;
}

// Checked on the binary itself: linking OpenImageIO (directly or through a library) would
// bring back its dynamic-linking cost on every run.
TEST(ImageModule, ProgramDoesNotLinkOpenImageIO)
{
    const std::string command = "readelf -d '" + cli_path().string() + "' 2>/dev/null";
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
    ASSERT_TRUE(pipe);
    std::string out;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe.get())) out += buffer;
    if (out.find("NEEDED") == std::string::npos) GTEST_SKIP() << "readelf is not available";
    std::printf("%s", out.c_str());
    EXPECT_EQ(out.find("OpenImageIO"), std::string::npos) << "geocold-cl links OpenImageIO";
}

// PFM, PPM and (for writing) PNG, the default output, are built in.
TEST(ImageModule, BuiltInFormatsNeedNoModule)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    for (const char* name : {"out.pfm", "out.png"}) {
        const TempDir dir;
        const RunResult r = render_to(dir / name, with_module(dir / "missing.so"));
        show(("-o " + std::string(name) + " without the module").c_str(), r);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(dir.entries(), std::vector<std::string>{name});
    }
}

// The format is checked before any device work: these need no OpenCL device.
TEST(ImageModule, MissingModuleIsAnOutputErrorNamingIt)
{
    const TempDir dir;
    const std::filesystem::path module = dir / "missing.so";
    const RunResult r = render_to(dir / "out.exr", with_module(module));
    show("-o out.exr, GEOCOLD_IMAGE_MODULE=<missing>", r);
    EXPECT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find("out.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(module.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("No such file or directory"), std::string::npos) << "dlerror()'s reason: " << r.err;
    EXPECT_EQ(r.count_err_lines("error:"), 1) << r.err;
    EXPECT_TRUE(dir.entries().empty()) << "something was written";
}

TEST(ImageModule, BrokenModuleIsAnOutputErrorNamingIt)
{
    const TempDir dir;
    const std::filesystem::path module = dir / "broken.so";
    write_file(module, "this is not a shared library\n");
    const RunResult r = render_to(dir / "out.exr", with_module(module));
    show("-o out.exr, GEOCOLD_IMAGE_MODULE=<not ELF>", r);
    EXPECT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find("cannot load the image module " + module.string()), std::string::npos) << r.err;
    EXPECT_EQ(r.count_err_lines("error:"), 1) << r.err;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"broken.so"}) << "something was written";
}

TEST(ImageModule, ModuleWithoutTheEntryPointIsRefused)
{
    const TempDir dir;
    const RunResult r = render_to(dir / "out.tif", with_module(GC_TEST_FOREIGN_MODULE));
    show("-o out.tif, GEOCOLD_IMAGE_MODULE=<a library without the entry point>", r);
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find(GC_TEST_FOREIGN_MODULE), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("gc_image_module_v1"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty()) << "something was written";
}

// A missing module also fails reading: an environment map that needs it is an input error.
TEST(ImageModule, MissingModuleWhenReadingIsAnInputError)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    write_file(dir / "sky.exr", "never read\n");
    std::vector<std::string> args = k_render;
    args.insert(args.end(), {"--env", (dir / "sky.exr").string(), "-o", (dir / "out.pfm").string()});
    const RunResult r = run_process(cli_path(), args, with_module(dir / "missing.so"));
    show("--env sky.exr, GEOCOLD_IMAGE_MODULE=<missing>", r);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("sky.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find((dir / "missing.so").string()), std::string::npos) << r.err;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"sky.exr"}) << "something was written";
}

}  // namespace
}  // namespace gc::test
