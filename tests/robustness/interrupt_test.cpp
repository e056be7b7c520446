// Ctrl-C during a long render, on a real terminal (a pty, so the progress bar is drawn):
// once = finish the sample, write the partial image with its true spp, exit 130;
// twice = quit at once, leaving no file behind.
#include <csignal>
#include <cstdio>

#include <gtest/gtest.h>

#include "host/image/image_io.h"
#include "process.h"

#if defined(GC_HAVE_OIIO)
#include <OpenImageIO/imageio.h>
#endif

namespace gc::test {
namespace {

const std::filesystem::path k_cornell = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";
constexpr unsigned k_requested_spp = 1000000;

// The spp the file says it holds, or -1.
int file_spp(const std::filesystem::path& path)
{
#if defined(GC_HAVE_OIIO)
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return -1;
    const int spp = in->spec().get_int_attribute("geocold:spp", -1);
    in->close();
    return spp;
#else
    (void)path;
    return -1;
#endif
}

TEST(Interrupt, CtrlCWritesThePartialImageAndExits130)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    // EXR carries the metadata; without OIIO the PFM is parsed and the spp comes from the log.
    const std::filesystem::path output = dir / (image_io_has_oiio() ? "partial.exr" : "partial.pfm");
    RunOptions options = cli_options();
    options.timeout_seconds = 300;
    bool sent = false;
    const RunResult r = run_on_terminal(
        cli_path(), {k_cornell.string(), "--spp", std::to_string(k_requested_spp), "--res", "64x64", "--device", "cpu", "-o", output.string()},
        options, [&](int pid, const std::string& so_far) {
            // The bar appears after the first sample, when the handler is installed.
            if (!sent && so_far.find("Rendering") != std::string::npos) {
                ::kill(pid, SIGINT);
                sent = true;
            }
        });
    std::printf("  terminal output:\n%s\n  -> %s after %.2f s\n", r.out.c_str(), r.describe().c_str(), r.seconds);
    ASSERT_TRUE(sent) << "no progress bar seen";
    ASSERT_FALSE(r.timed_out);
    ASSERT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exit_code, 130);
    EXPECT_NE(r.out.find("interrupted"), std::string::npos);

    // The log line and the file agree on a spp below the request.
    const std::string tag = "(64x64, ";
    const std::size_t at = r.out.find(tag);
    ASSERT_NE(at, std::string::npos) << "no 'wrote' line";
    const unsigned long logged = std::stoul(r.out.substr(at + tag.size()));
    std::printf("  log says %lu spp of %u requested\n", logged, k_requested_spp);
    EXPECT_GE(logged, 1u);
    EXPECT_LT(logged, k_requested_spp);
    ASSERT_TRUE(std::filesystem::is_regular_file(output));
    const Film film = read_image(output);  // a complete, parseable image
    EXPECT_EQ(film.width(), 64u);
    EXPECT_EQ(film.height(), 64u);
    if (image_io_has_oiio()) {
        const int spp = file_spp(output);
        std::printf("  file metadata geocold:spp = %d\n", spp);
        EXPECT_EQ(spp, static_cast<int>(logged));
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{output.filename().string()}) << "temp files left behind";
}

TEST(Interrupt, SecondCtrlCQuitsAtOnceWithoutAFile)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const std::filesystem::path output = dir / "never.pfm";
    RunOptions options = cli_options();
    options.timeout_seconds = 300;
    int sent = 0;
    // Large samples, so the second Ctrl-C lands while the first one's sample still runs.
    const RunResult r = run_on_terminal(
        cli_path(), {k_cornell.string(), "--spp", "100000", "--res", "1024x1024", "--device", "cpu", "-o", output.string()},
        options, [&](int pid, const std::string& so_far) {
            if (sent == 0 && so_far.find("Rendering") != std::string::npos) {
                ::kill(pid, SIGINT);
                sent = 1;
            } else if (sent == 1 && so_far.find("Ctrl-C again") != std::string::npos) {
                ::kill(pid, SIGINT);
                sent = 2;
            }
        });
    std::printf("  -> %s after %.2f s\n", r.describe().c_str(), r.seconds);
    ASSERT_EQ(sent, 2) << r.out;
    ASSERT_FALSE(r.timed_out);
    EXPECT_EQ(r.signal, SIGINT) << r.describe() << "\n" << r.out;
    EXPECT_TRUE(dir.entries().empty()) << "left behind: " << dir.entries().front();
}

}  // namespace
}  // namespace gc::test
