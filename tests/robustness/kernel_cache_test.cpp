// The kernel binary cache seen from outside (issue item 6): a truncated, corrupted or
// foreign (well-formed, but a payload the driver rejects) entry is noticed, rebuilt from
// source, and the image is bit-identical to the one from a clean cache.
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "host/cl/binary_cache.h"
#include "process.h"

namespace gc::test {
namespace {

const std::filesystem::path k_cornell = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";

std::vector<std::filesystem::path> entries(const std::filesystem::path& dir)
{
    std::vector<std::filesystem::path> out;
    if (std::filesystem::is_directory(dir))
        for (const auto& e : std::filesystem::directory_iterator(dir))
            if (e.path().extension() == ".clbin") out.push_back(e.path());
    return out;
}

TEST(KernelCache, DamagedEntriesAreRebuiltAndGiveTheSameImage)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    const TempDir dir;
    const std::filesystem::path cache = dir / "cache";
    RunOptions options = cli_options();
    options.env["GEOCOLD_CACHE_DIR"] = cache.string();
    options.env["GEOCOLD_CACHE_ALWAYS"] = "1"; // PoCL's own kcache would otherwise stand in for ours
    auto render = [&](const std::string& name) {
        const std::filesystem::path out = dir / (name + ".pfm");
        const RunResult r = run_process(
            cli_path(), {k_cornell.string(), "--spp", "2", "--res", "24x24", "--device", "cpu", "-v", "-o", out.string()}, options);
        std::string cache_lines;
        std::istringstream lines(r.err);
        for (std::string line; std::getline(lines, line);)
            if (line.find("cache") != std::string::npos) cache_lines += "\n    " + line;
        std::printf("  %s -> %s (%.2f s)%s\n", name.c_str(), r.describe().c_str(), r.seconds, cache_lines.c_str());
        EXPECT_EQ(r.signal, 0) << name;
        EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.err;
        return std::make_pair(read_file(out), r.err);
    };

    const auto [clean, clean_log] = render("clean");
    ASSERT_FALSE(clean.empty());
    const std::vector<std::filesystem::path> stored = entries(cache);
    if (stored.empty()) GTEST_SKIP() << "the kernel cache is not written by this build (nothing to damage)";
    const auto [warm, warm_log] = render("warm");
    EXPECT_EQ(warm, clean);
    EXPECT_NE(warm_log.find("from cache"), std::string::npos) << "second run did not use the cache";

    struct Damage {
        const char* name;
        std::function<void(const std::filesystem::path&)> apply;
    };
    const std::vector<Damage> damages = {
        {"truncated", [](const std::filesystem::path& p) { std::filesystem::resize_file(p, std::filesystem::file_size(p) / 2); }},
        {"bit-flipped", [](const std::filesystem::path& p) {
             std::string bytes = read_file(p);
             bytes[bytes.size() * 3 / 4] ^= 0x10;
             write_file(p, bytes);
         }},
        {"empty", [](const std::filesystem::path& p) { write_file(p, ""); }},
        {"foreign", [&](const std::filesystem::path& p) {
             // Well-formed entry with a valid checksum whose payload no driver accepts: what an
             // entry from another driver version would look like if the keys ever collided.
             const std::uint64_t key = std::stoull(p.stem().string(), nullptr, 16);
             const std::string junk = "not a program binary for this device";
             cl::BinaryCache(cache).store(key, std::span(reinterpret_cast<const unsigned char*>(junk.data()), junk.size()));
         }},
    };
    for (const Damage& d : damages) {
        for (const std::filesystem::path& p : entries(cache)) d.apply(p);
        const auto [image, log] = render(d.name);
        EXPECT_EQ(image, clean) << d.name << ": the image differs from the clean-cache one";
        EXPECT_NE(log.find("from source (cache:"), std::string::npos) << d.name << ": damage not noticed\n" << log;
        // Rebuilt and stored again: the next run is a clean hit.
        const auto [again, again_log] = render(std::string(d.name) + "-then-warm");
        EXPECT_EQ(again, clean);
        EXPECT_NE(again_log.find("from cache"), std::string::npos) << d.name << ": not re-cached";
    }
}

}  // namespace
}  // namespace gc::test
