#include "host/cl/binary_cache.h"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

namespace gc::cl {
namespace {

constexpr char magic[8] = {'G', 'C', 'C', 'L', 'B', 'I', 'N', '\0'};

template <class T>
void put(std::vector<unsigned char>& out, T value)
{
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.insert(out.end(), bytes, bytes + sizeof(T));
}

template <class T>
T get(const unsigned char* at)
{
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

bool fail(std::string* why, std::string reason)
{
    if (why) *why = std::move(reason);
    return false;
}

}  // namespace

void Fnv1a::add(const void* data, size_t size)
{
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
        m_state ^= bytes[i];
        m_state *= 0x100000001b3ull;
    }
}

void Fnv1a::add_field(std::string_view text)
{
    const std::uint64_t size = text.size();
    add(&size, sizeof size);
    add(text.data(), text.size());
}

std::uint64_t fnv1a64(std::span<const unsigned char> data)
{
    Fnv1a hash;
    hash.add(data.data(), data.size());
    return hash.value();
}

std::string to_hex(std::uint64_t value)
{
    static const char digits[] = "0123456789abcdef";
    std::string text(16, '0');
    for (int i = 15; i >= 0; --i, value >>= 4) text[static_cast<size_t>(i)] = digits[value & 15];
    return text;
}

std::optional<std::filesystem::path> user_cache_dir(std::string_view xdg_cache_home, std::string_view home)
{
    if (!xdg_cache_home.empty()) return std::filesystem::path(xdg_cache_home) / "geocold-cl" / "kernels";
    if (!home.empty()) return std::filesystem::path(home) / ".cache" / "geocold-cl" / "kernels";
    return std::nullopt;
}

std::filesystem::path BinaryCache::entry_path(std::uint64_t key) const
{
    return m_dir / (to_hex(key) + ".clbin");
}

std::optional<std::vector<unsigned char>> BinaryCache::load(std::uint64_t key,
                                                            std::string* why) const
{
    const std::filesystem::path path = entry_path(key);
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        fail(why, "no entry " + path.string());
        return std::nullopt;
    }
    std::vector<unsigned char> file((std::istreambuf_iterator<char>(in)),
                                    std::istreambuf_iterator<char>());
    if (in.bad()) {
        fail(why, "cannot read " + path.string());
        return std::nullopt;
    }
    auto reject = [&](const std::string& reason) {
        fail(why, path.string() + ": " + reason);
        return std::nullopt;
    };
    if (file.size() < header_size)
        return reject("truncated header (" + std::to_string(file.size()) + " bytes)");
    const unsigned char* h = file.data();
    if (std::memcmp(h, magic, sizeof magic) != 0) return reject("bad magic");
    if (get<std::uint32_t>(h + 8) != format_version) return reject("unknown format version");
    if (get<std::uint32_t>(h + 12) != header_size) return reject("bad header size");
    if (get<std::uint64_t>(h + 16) != key) return reject("key mismatch");
    const auto payload_size = get<std::uint64_t>(h + 24);
    if (payload_size != file.size() - header_size) {
        return reject("payload is " + std::to_string(file.size() - header_size) +
                      " bytes, header says " + std::to_string(payload_size));
    }
    std::vector<unsigned char> payload(file.begin() + header_size, file.end());
    if (payload.empty()) return reject("empty payload");
    if (fnv1a64(payload) != get<std::uint64_t>(h + 32)) return reject("checksum mismatch");
    return payload;
}

bool BinaryCache::store(std::uint64_t key, std::span<const unsigned char> payload,
                        std::string* why) const
{
    std::error_code ec;
    std::filesystem::create_directories(m_dir, ec);
    if (ec) return fail(why, "cannot create " + m_dir.string() + ": " + ec.message());

    // Built from the magic rather than insert()ed after reserve(): GCC 12 at -O3 flags the
    // latter with a false -Wstringop-overflow.
    std::vector<unsigned char> file(magic, magic + sizeof magic);
    file.reserve(header_size + payload.size());
    put<std::uint32_t>(file, format_version);
    put<std::uint32_t>(file, static_cast<std::uint32_t>(header_size));
    put<std::uint64_t>(file, key);
    put<std::uint64_t>(file, payload.size());
    put<std::uint64_t>(file, fnv1a64(payload));
    file.insert(file.end(), payload.begin(), payload.end());

    // A unique temp name per process and call, in the same directory so rename is atomic.
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path final_path = entry_path(key);
    const std::filesystem::path temp = final_path.string() + ".tmp." + std::to_string(::getpid()) +
                                       "." + std::to_string(counter++);
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(file.data()),
                  static_cast<std::streamsize>(file.size()));
        out.close();
        if (!out) {
            std::filesystem::remove(temp, ec);
            return fail(why, "cannot write " + temp.string());
        }
    }
    std::filesystem::rename(temp, final_path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        return fail(why, "cannot rename " + temp.string() + " to " + final_path.string() + ": " +
                             ec.message());
    }
    return true;
}

void BinaryCache::remove(std::uint64_t key) const noexcept
{
    std::error_code ignored;
    std::filesystem::remove(entry_path(key), ignored);
}

}  // namespace gc::cl
