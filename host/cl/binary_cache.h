// On-disk cache of compiled program binaries, so a warm start compiles nothing.
//
// An entry is <dir>/<key as 16 hex digits>.clbin: a 40-byte header (magic "GCCLBIN\0",
// format version, header size, key, payload size, FNV-1a checksum of the payload) and the
// driver's binary. Entries are written to a temp file and renamed into place, so a reader
// sees a whole entry or none; a crash leaves at most a stray temp file. Anything that does
// not verify is reported as a miss with the reason, never trusted.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gc::cl {

// 64-bit FNV-1a (Fowler, Noll, Vo). Not cryptographic: it detects edits and corruption,
// which is all a local cache needs.
class Fnv1a {
public:
    void add(const void* data, size_t size);
    // Adds the length first, so ("ab","c") and ("a","bc") hash differently.
    void add_field(std::string_view text);
    std::uint64_t value() const { return m_state; }

private:
    std::uint64_t m_state = 0xcbf29ce484222325ull;
};

std::uint64_t fnv1a64(std::span<const unsigned char> data);
std::string to_hex(std::uint64_t value);  // 16 lowercase hex digits

// The per-user cache folder, following the XDG base directory rules: <xdg_cache_home>/
// geocold-cl/kernels, else <home>/.cache/geocold-cl/kernels; nullopt when both are empty.
std::optional<std::filesystem::path> user_cache_dir(std::string_view xdg_cache_home, std::string_view home);

class BinaryCache {
public:
    explicit BinaryCache(std::filesystem::path dir) : m_dir(std::move(dir)) {}

    const std::filesystem::path& dir() const { return m_dir; }
    std::filesystem::path entry_path(std::uint64_t key) const;

    // The payload stored under key, or nullopt with the reason in *why ("no entry", "truncated
    // header", "checksum mismatch", ...).
    std::optional<std::vector<unsigned char>> load(std::uint64_t key,
                                                   std::string* why = nullptr) const;
    // Writes atomically; false with the reason on any failure (a cache is best effort).
    bool store(std::uint64_t key, std::span<const unsigned char> payload,
               std::string* why = nullptr) const;
    void remove(std::uint64_t key) const noexcept;

    static constexpr std::uint32_t format_version = 1;
    static constexpr size_t header_size = 40;

private:
    std::filesystem::path m_dir;
};

}  // namespace gc::cl
