// A scene or image too large for the device: a clear DeviceError naming the buffer and the
// sizes (exit 4), before anything is launched — through the library and through the CLI.
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "host/bvh/bvh.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/render/renderer.h"
#include "host/scene/camera_framing.h"
#include "host/scene/load.h"
#include "process.h"

namespace gc::test {
namespace {

const std::filesystem::path k_cornell = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";

// The CPU device with its largest single allocation shrunk to `max_alloc` bytes: the checks
// in cl::Buffer::create see the small limit, the driver is never asked.
cl::DeviceInfo small_device(cl_ulong max_alloc)
{
    cl::DeviceInfo device = cl::select_device("cpu");
    device.max_alloc = max_alloc;
    return device;
}

std::string device_error(const std::function<void()>& f)
{
    try {
        f();
    } catch (const DeviceError& e) {
        EXPECT_EQ(e.code(), ExitCode::Device);
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected DeviceError, got: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected DeviceError, nothing was thrown";
    return {};
}

TEST(Resources, BufferOverMaxAllocNamesBufferAndSizes)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const cl::Context context(small_device(1024));
    const std::string msg = device_error([&] { cl::Buffer<float>::create(context, 1000, CL_MEM_READ_WRITE, "triangles"); });
    std::printf("  %s\n", msg.c_str());
    for (const char* part : {"'triangles'", "1000 elements of 4 bytes", "(1024 bytes)", "largest single allocation"})
        EXPECT_NE(msg.find(part), std::string::npos) << part;
    // At the limit is fine.
    EXPECT_NO_THROW(cl::Buffer<float>::create(context, 256, CL_MEM_READ_WRITE, "fits"));
    // A count whose byte size overflows size_t is refused the same way, not wrapped.
    const std::string huge = device_error([&] {
        cl::Buffer<float>::create(context, std::numeric_limits<size_t>::max() / 2, CL_MEM_READ_WRITE, "huge");
    });
    std::printf("  %s\n", huge.c_str());
    EXPECT_NE(huge.find("'huge'"), std::string::npos);
}

TEST(Resources, SceneLargerThanMaxAllocIsADeviceError)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const Scene scene = load_scene(k_cornell);
    const FlatBvh bvh = build_bvh(scene);
    RenderSettings settings;
    settings.width = 8;
    settings.height = 8;
    settings.spp = 1;
    // 8x8 film of float4 = 1 KiB fits; the scene's triangle data (32 triangles) does not.
    const cl::Context context(small_device(1024));
    const std::string msg = device_error([&] { Renderer renderer(context, scene, bvh, frame_camera(scene), settings); });
    std::printf("  %s\n", msg.c_str());
    EXPECT_NE(msg.find("cannot allocate buffer '"), std::string::npos);
    EXPECT_NE(msg.find("exceeds the largest single allocation of"), std::string::npos);
    EXPECT_NE(msg.find("(1024 bytes)"), std::string::npos);
}

// Through the CLI, with PoCL told it has 1 GiB (its largest allocation becomes 256 MiB):
// an 8192x8192 float film needs 1 GiB.
TEST(Resources, CliFilmOverMaxAllocExits4)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const cl::DeviceInfo cpu = cl::select_device("cpu");
    if (cpu.platform_name.find("Portable Computing Language") == std::string::npos)
        GTEST_SKIP() << "POCL_MEMORY_LIMIT needs PoCL; the CPU device is " << cpu.platform_name;
    const TempDir dir;
    RunOptions options = cli_options();
    options.env["POCL_MEMORY_LIMIT"] = "1";
    const RunResult r = run_process(
        cli_path(), {k_cornell.string(), "--spp", "1", "--res", "8192x8192", "--device", "cpu", "-o", (dir / "big.png").string()},
        options);
    std::printf("  -> %s (%.2f s)\n    %s", r.describe().c_str(), r.seconds, r.err.c_str());
    EXPECT_EQ(r.signal, 0);
    EXPECT_EQ(r.exit_code, 4);
    EXPECT_NE(r.err.find("cannot allocate buffer '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("exceeds the largest single allocation of 256 MiB (268435456 bytes)"), std::string::npos) << r.err;
    EXPECT_EQ(r.count_err_lines("error:"), 1);
    EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace gc::test
