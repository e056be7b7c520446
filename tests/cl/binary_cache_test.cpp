#include "host/cl/binary_cache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "cl_test_util.h"

namespace gc::cl {
namespace {

using test::TempDir;

std::vector<unsigned char> bytes_of(const std::string& text)
{
    return {text.begin(), text.end()};
}

TEST(Fnv1a, ReferenceVectors)
{
    // Published FNV-1a 64 test vectors.
    EXPECT_EQ(fnv1a64(bytes_of("")), 0xcbf29ce484222325ull);
    EXPECT_EQ(fnv1a64(bytes_of("a")), 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(fnv1a64(bytes_of("foobar")), 0x85944171f73967e8ull);
    EXPECT_EQ(to_hex(0x85944171f73967e8ull), "85944171f73967e8");
    EXPECT_EQ(to_hex(1), "0000000000000001");
}

TEST(Fnv1a, FieldsAreLengthPrefixed)
{
    Fnv1a a, b;
    a.add_field("ab");
    a.add_field("c");
    b.add_field("a");
    b.add_field("bc");
    EXPECT_NE(a.value(), b.value());
}

TEST(BinaryCache, RoundTrip)
{
    TempDir dir;
    const BinaryCache cache(dir.path() / "nested" / "kernels");
    const auto payload = bytes_of("not really a binary, but bytes all the same");
    std::string why;
    EXPECT_FALSE(cache.load(42, &why));
    EXPECT_NE(why.find("no entry"), std::string::npos) << why;
    ASSERT_TRUE(cache.store(42, payload, &why)) << why;
    const auto loaded = cache.load(42, &why);
    ASSERT_TRUE(loaded) << why;
    EXPECT_EQ(*loaded, payload);
    EXPECT_EQ(std::filesystem::file_size(cache.entry_path(42)),
              BinaryCache::header_size + payload.size());
    // The atomic write leaves no temp file behind.
    size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(cache.dir()))
        ++files;
    EXPECT_EQ(files, 1u);
    cache.remove(42);
    EXPECT_FALSE(std::filesystem::exists(cache.entry_path(42)));
}

// Every way an entry can be damaged is reported as a miss with a reason.
TEST(BinaryCache, RejectsDamagedEntries)
{
    TempDir dir;
    const BinaryCache cache(dir.path());
    const auto payload = bytes_of("0123456789abcdef0123456789abcdef");
    const auto path = cache.entry_path(7);
    auto damage = [&](auto&& edit) {
        ASSERT_TRUE(cache.store(7, payload));
        std::vector<char> file(std::filesystem::file_size(path));
        std::ifstream(path, std::ios::binary)
            .read(file.data(), static_cast<std::streamsize>(file.size()));
        edit(file);
        std::ofstream(path, std::ios::binary | std::ios::trunc)
            .write(file.data(), static_cast<std::streamsize>(file.size()));
    };
    struct Case {
        const char* name;
        std::function<void(std::vector<char>&)> edit;
        const char* reason;
    };
    const std::vector<Case> cases = {
        {"truncated header", [](std::vector<char>& f) { f.resize(20); }, "truncated header"},
        {"truncated payload", [](std::vector<char>& f) { f.resize(f.size() - 5); }, "header says"},
        {"flipped payload byte",
         [](std::vector<char>& f) { f[BinaryCache::header_size + 3] ^= 0x10; }, "checksum"},
        {"flipped magic", [](std::vector<char>& f) { f[0] ^= 0x01; }, "bad magic"},
        {"flipped key", [](std::vector<char>& f) { f[16] ^= 0x01; }, "key mismatch"},
        {"empty file", [](std::vector<char>& f) { f.clear(); }, "truncated header"},
    };
    for (const Case& c : cases) {
        damage(c.edit);
        std::string why;
        EXPECT_FALSE(cache.load(7, &why)) << c.name;
        std::printf("%-22s -> %s\n", c.name, why.c_str());
        EXPECT_NE(why.find(c.reason), std::string::npos) << c.name << ": " << why;
    }
    // A valid entry under another key is not returned for this one.
    ASSERT_TRUE(cache.store(8, payload));
    std::filesystem::copy_file(cache.entry_path(8), path,
                               std::filesystem::copy_options::overwrite_existing);
    EXPECT_FALSE(cache.load(7));
}

TEST(BinaryCache, StoreFailsSoftlyWhenDirectoryIsAFile)
{
    TempDir dir;
    test::write_file(dir.path() / "file", "x");
    const BinaryCache cache(dir.path() / "file" / "sub");
    std::string why;
    EXPECT_FALSE(cache.store(1, bytes_of("payload"), &why));
    std::printf("store failure: %s\n", why.c_str());
    EXPECT_FALSE(why.empty());
}

TEST(UserCacheDir, XdgCacheHomeThenHome)
{
    EXPECT_EQ(user_cache_dir("", "/home/someone"),
              std::filesystem::path("/home/someone/.cache/geocold-cl/kernels"));
    EXPECT_EQ(user_cache_dir("/xdg", "/home/someone"),
              std::filesystem::path("/xdg/geocold-cl/kernels"));
    EXPECT_EQ(user_cache_dir("", ""), std::nullopt);
}

}  // namespace
}  // namespace gc::cl
