#include "host/cl/program.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cl_test_util.h"
#include "host/cl/binary_cache.h"
#include "host/cl/buffer.h"
#include "host/util/log.h"
#include "test_kernels.h"

namespace gc::cl {
namespace {

namespace fs = std::filesystem;

class ProgramTest : public test::DeviceTest {
protected:
    void SetUp() override
    {
        DeviceTest::SetUp();
        if (IsSkipped()) return;
        dir.write("compute.cl", test::compute_cl);
        config = BuildConfig{dir.path(), cache.path(), true};
        config.store_when_driver_caches = true;  // these tests are about our cache, on any driver
    }

    std::vector<float> run(const Program& program, cl_uint n = 777)
    {
        Kernel kernel = program.kernel("compute");
        auto data = Buffer<float>::create(*context, n, CL_MEM_READ_WRITE, "data");
        kernel.set_args(data, n, 3.0f);
        kernel.launch(*context, n, 0, "compute");
        std::vector<float> out(n);
        data.read(out);
        return out;
    }

    // Expected values on the host, for a sanity check with the tolerance OpenCL allows.
    static void expect_plausible(const std::vector<float>& out, float scale = 1.0f)
    {
        for (size_t i = 0; i < out.size(); i += 97) {
            const double x = static_cast<double>(i) + 0.5;
            EXPECT_NEAR(out[i], std::sqrt(x) / (x + 3.0) * scale, 1e-5 * scale) << i;
        }
    }

    fs::path only_entry() const
    {
        std::vector<fs::path> entries;
        for (const auto& e : fs::directory_iterator(cache.path())) entries.push_back(e.path());
        EXPECT_EQ(entries.size(), 1u);
        return entries.empty() ? fs::path() : entries.front();
    }

    test::TempKernelDir dir;
    test::TempDir cache;
    BuildConfig config;
};

TEST_F(ProgramTest, SyntaxErrorGivesBuildLog)
{
    dir.write("broken.cl",
              "__kernel void k(__global float* x)\n{\n    x[0] = undeclared_thing;\n}\n");
    try {
        Program program(*context, "broken.cl", "", config);
        FAIL() << "a broken kernel built";
    } catch (const ClBuildError& e) {
        const std::string message = e.what();
        std::printf("%s\n", message.c_str());
        EXPECT_EQ(e.code(), CL_BUILD_PROGRAM_FAILURE);
        EXPECT_NE(e.log().find("undeclared_thing"), std::string::npos) << e.log();
        EXPECT_NE(message.find(e.log()), std::string::npos);
        EXPECT_NE(message.find("'broken.cl'"), std::string::npos);
        // The log names the real file and the right line (drivers say "<kernel>" or "<source>").
        EXPECT_NE(e.log().find("broken.cl:3:"), std::string::npos) << e.log();
    }
    EXPECT_TRUE(fs::is_empty(cache.path())) << "a failed build must not leave a cache entry";
}

TEST_F(ProgramTest, MissingFileIsNamed)
{
    try {
        Program program(*context, "missing.cl", "", config);
        FAIL();
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.cl"), std::string::npos) << e.what();
    }
}

TEST_F(ProgramTest, ColdThenWarmGivesIdenticalResults)
{
    Program cold(*context, "compute.cl", "", config);
    EXPECT_FALSE(cold.from_cache());
    const std::vector<float> a = run(cold);
    expect_plausible(a);
    const fs::path entry = only_entry();
    EXPECT_EQ(entry.filename().string(), to_hex(cold.cache_key()) + ".clbin");

    Program warm(*context, "compute.cl", "", config);
    EXPECT_TRUE(warm.from_cache());
    EXPECT_EQ(warm.cache_key(), cold.cache_key());
    const std::vector<float> b = run(warm);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)))
        << "cached binary computes differently";
    std::printf("options: %s\ncold %.3f s, warm %.3f s\n", cold.options().c_str(),
                cold.build_seconds(), warm.build_seconds());
    EXPECT_EQ(cold.options().find("fast-relaxed"), std::string::npos);
}

TEST_F(ProgramTest, CorruptCacheEntriesAreRebuilt)
{
    const std::vector<float> reference = run(Program(*context, "compute.cl", "", config));
    const fs::path entry = only_entry();

    // Verbose logging prints why each entry was rejected (the reason the rebuild happened).
    const LogLevel saved_level = log_level();
    set_log_level(LogLevel::Verbose);
    auto check_rebuilds = [&](const char* what, auto&& damage) {
        damage();
        Program program(*context, "compute.cl", "", config);
        EXPECT_FALSE(program.from_cache()) << what;
        const std::vector<float> out = run(program);
        EXPECT_EQ(0, std::memcmp(out.data(), reference.data(), out.size() * sizeof(float))) << what;
        // The bad entry was replaced by a good one. (Not necessarily byte-identical: PoCL bundles
        // its own per-kernel cache into the binary, which grows once a kernel has run.)
        EXPECT_TRUE(BinaryCache(cache.path()).load(program.cache_key()).has_value()) << what;
        EXPECT_TRUE(Program(*context, "compute.cl", "", config).from_cache()) << what;
        std::printf("%s: rebuilt, results identical\n", what);
    };
    check_rebuilds("truncated", [&] { fs::resize_file(entry, fs::file_size(entry) / 2); });
    check_rebuilds("flipped byte", [&] {
        const auto at = static_cast<std::streamoff>(fs::file_size(entry) - 10);
        std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(at);
        char c = 0;
        f.read(&c, 1);
        c = static_cast<char>(c ^ 0x5a);
        f.seekp(at);
        f.write(&c, 1);
    });
    check_rebuilds("empty", [&] { fs::resize_file(entry, 0); });
    // A well-formed entry whose payload the driver cannot load: checksum and key are right, so
    // only clCreateProgramWithBinary / clBuildProgram can reject it.
    check_rebuilds("garbage binary", [&] {
        const BinaryCache store(cache.path());
        const uint64_t key = std::stoull(entry.stem().string(), nullptr, 16);
        std::vector<unsigned char> junk(4096);
        for (size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<unsigned char>(i * 131 + 7);
        ASSERT_TRUE(store.store(key, junk));
        ASSERT_TRUE(store.load(key).has_value());
    });
    set_log_level(saved_level);
}

TEST_F(ProgramTest, OptionsOrSourceChangeMisses)
{
    Program one(*context, "compute.cl", "-D SCALE=2.0f", config);
    EXPECT_FALSE(one.from_cache());
    expect_plausible(run(one), 2.0f);

    Program two(*context, "compute.cl", "-D SCALE=3.0f", config);
    EXPECT_FALSE(two.from_cache()) << "different options must not share a binary";
    EXPECT_NE(one.cache_key(), two.cache_key());
    expect_plausible(run(two), 3.0f);

    EXPECT_TRUE(Program(*context, "compute.cl", "-D SCALE=2.0f", config).from_cache());

    // Editing any header under the kernel dir (even one compute.cl does not include) changes the
    // key.
    dir.write("shared/extra.h", "#define GC_EXTRA 1\n");
    Program three(*context, "compute.cl", "-D SCALE=2.0f", config);
    EXPECT_FALSE(three.from_cache());
    EXPECT_NE(three.cache_key(), one.cache_key());
}

TEST_F(ProgramTest, CacheCanBeDisabled)
{
    BuildConfig off = config;
    off.use_cache = false;
    EXPECT_FALSE(Program(*context, "compute.cl", "", off).from_cache());
    EXPECT_FALSE(Program(*context, "compute.cl", "", off).from_cache());
    EXPECT_TRUE(fs::is_empty(cache.path()));

    // No cache folder, no cache.
    const BuildConfig nowhere{dir.path(), {}, true};
    EXPECT_FALSE(Program(*context, "compute.cl", "", nowhere).from_cache());
    EXPECT_FALSE(Program(*context, "compute.cl", "", nowhere).from_cache());
}

// PoCL caches builds itself; by default we then read entries but do not write them, because
// asking PoCL for a binary doubles the work-group function compiles (program.cpp).
TEST_F(ProgramTest, PoclBuildsAreLeftToPoclsOwnCache)
{
    if (context->device().platform_name.find("Portable Computing Language") == std::string::npos)
        GTEST_SKIP() << "not a PoCL device";
    BuildConfig plain = config;
    plain.store_when_driver_caches = false;
    const Program program(*context, "compute.cl", "", plain);
    EXPECT_FALSE(program.from_cache());
    expect_plausible(run(program));
    EXPECT_TRUE(fs::is_empty(cache.path())) << "a PoCL build wrote a binary cache entry";

    // With PoCL's cache off, ours is the only one and is written again.
    plain.driver_cache_disabled = true;
    const Program uncached(*context, "compute.cl", "", plain);
    EXPECT_FALSE(fs::is_empty(cache.path())) << "PoCL's cache is off but no entry of ours";
}

TEST_F(ProgramTest, KernelDirFromConfig)
{
    const BuildConfig chosen{dir.path(), cache.path(), true};
    Program program(*context, "compute.cl", "", chosen);
    expect_plausible(run(program));
    EXPECT_NE(program.options().find("-I " + (dir.path() / "shared").string()), std::string::npos);
}

// The probes in kernels/test (tests and bench only) stay out of the product programs' source
// hash, so editing one leaves every user's cache valid; a probe's own hash covers them.
TEST_F(ProgramTest, ProbesStayOutOfTheProductHash)
{
    auto source_hash = [](const Program& p) {
        const std::string& o = p.options();
        const auto at = o.find("GC_SOURCE_HASH=");
        return at == std::string::npos ? std::string() : o.substr(at, o.find(' ', at) - at);
    };
    fs::create_directories(dir.path() / "test");
    dir.write("test/probe.cl", test::compute_cl);
    const std::string product_before = source_hash(Program(*context, "compute.cl", "", config));
    const std::string probe_before = source_hash(Program(*context, "test/probe.cl", "", config));
    dir.write("test/probe.cl", std::string(test::compute_cl) + "\n/* edited */\n");
    const std::string product_after = source_hash(Program(*context, "compute.cl", "", config));
    const std::string probe_after = source_hash(Program(*context, "test/probe.cl", "", config));
    std::printf("product %s -> %s; probe %s -> %s\n", product_before.c_str(), product_after.c_str(),
                probe_before.c_str(), probe_after.c_str());
    ASSERT_FALSE(product_before.empty());
    EXPECT_EQ(product_before, product_after);
    EXPECT_NE(probe_before, probe_after);
    dir.write("shared/gc_extra.h", "/* a new shared header */\n");
    EXPECT_NE(source_hash(Program(*context, "compute.cl", "", config)), product_after);
}

}  // namespace
}  // namespace gc::cl
