#include "host/image/exr_writer.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <set>

#include "host/image/atomic_file.h"
#include "host/util/error.h"

namespace gc {
namespace {

static_assert(std::endian::native == std::endian::little, "the EXR code writes the host's bytes as little-endian");

constexpr std::uint32_t k_magic = 20000630;  // 0x762f3101
constexpr std::uint32_t k_version = 2;
constexpr std::uint32_t k_multipart_flag = 0x1000;

class Bytes {
public:
    std::string data;
    template <class T>
    void value(T v)
    {
        data.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void text0(const std::string& s)
    {
        data += s;
        data += '\0';
    }
    void attribute(const std::string& name, const std::string& type, const std::string& bytes)
    {
        text0(name);
        text0(type);
        value(std::int32_t(bytes.size()));
        data += bytes;
    }
};

template <class T>
std::string raw(const T& v)
{
    return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}

std::vector<const ExrChannel*> sorted_channels(const ExrPart& part)
{
    std::vector<const ExrChannel*> out;
    for (const ExrChannel& c : part.channels) out.push_back(&c);
    std::sort(out.begin(), out.end(), [](const ExrChannel* a, const ExrChannel* b) { return a->name < b->name; });
    return out;
}

void write_header(Bytes& w, const ExrPart& part, const std::vector<const ExrChannel*>& channels,
                  std::uint32_t width, std::uint32_t height, bool multipart)
{
    Bytes chlist;
    for (const ExrChannel* c : channels) {
        chlist.text0(c->name);
        chlist.value(static_cast<std::int32_t>(c->type));
        chlist.value(std::uint32_t(0));  // pLinear and three reserved bytes
        chlist.value(std::int32_t(1));   // x and y sampling
        chlist.value(std::int32_t(1));
    }
    chlist.value(std::uint8_t(0));
    w.attribute("channels", "chlist", chlist.data);
    w.attribute("compression", "compression", std::string(1, '\0'));
    const std::int32_t window[4] = {0, 0, std::int32_t(width) - 1, std::int32_t(height) - 1};
    w.attribute("dataWindow", "box2i", raw(window));
    w.attribute("displayWindow", "box2i", raw(window));
    w.attribute("lineOrder", "lineOrder", std::string(1, '\0'));
    w.attribute("pixelAspectRatio", "float", raw(1.0f));
    const float center[2] = {0.0f, 0.0f};
    w.attribute("screenWindowCenter", "v2f", raw(center));
    w.attribute("screenWindowWidth", "float", raw(1.0f));
    if (multipart) {
        w.attribute("name", "string", part.name);
        w.attribute("type", "string", "scanlineimage");
        w.attribute("chunkCount", "int", raw(std::int32_t(height)));  // one scan line per chunk
    }
    for (const auto& [key, value] : part.text) w.attribute(key, "string", value);
    w.value(std::uint8_t(0));
}

}  // namespace

std::string encode_exr(std::uint32_t width, std::uint32_t height, const std::vector<ExrPart>& parts)
{
    if (parts.empty()) throw UsageError("an EXR file needs at least one part");
    const bool multipart = parts.size() > 1 || !parts.front().name.empty();
    const std::size_t pixels = std::size_t(width) * height;
    std::set<std::string> names;
    for (const ExrPart& p : parts) {
        if (multipart && (p.name.empty() || !names.insert(p.name).second))
            throw UsageError("EXR part name '" + p.name + "' is empty or repeated");
        for (const ExrChannel& c : p.channels)
            if (c.bits.size() != pixels)
                throw UsageError("EXR channel '" + c.name + "' holds " + std::to_string(c.bits.size()) +
                                 " values for " + std::to_string(pixels) + " pixels");
    }

    Bytes w;
    w.value(k_magic);
    w.value(multipart ? k_version | k_multipart_flag : k_version);
    std::vector<std::vector<const ExrChannel*>> channels;
    for (const ExrPart& p : parts) {
        channels.push_back(sorted_channels(p));
        write_header(w, p, channels.back(), width, height, multipart);
    }
    if (multipart) w.value(std::uint8_t(0));  // the empty header that ends the list

    // Offset tables (one per part), then each part's scan lines, each prefixed by its part
    // number in a multi-part file.
    const std::size_t chunk_prefix = (multipart ? 12 : 8);
    std::uint64_t offset = w.data.size() + 8ull * height * parts.size();
    for (const auto& list : channels) {
        const std::uint64_t line_bytes = std::uint64_t(width) * 4 * list.size();
        for (std::uint32_t y = 0; y < height; ++y) {
            w.value(offset);
            offset += chunk_prefix + line_bytes;
        }
    }
    w.data.reserve(static_cast<std::size_t>(offset));
    for (std::size_t p = 0; p < parts.size(); ++p) {
        const std::size_t line_bytes = std::size_t(width) * 4 * channels[p].size();
        for (std::uint32_t y = 0; y < height; ++y) {
            if (multipart) w.value(std::int32_t(p));
            w.value(std::int32_t(y));
            w.value(std::int32_t(line_bytes));
            for (const ExrChannel* c : channels[p])
                w.data.append(reinterpret_cast<const char*>(c->bits.data() + std::size_t(y) * width), 4 * width);
        }
    }
    return std::move(w.data);
}

void write_exr(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               const std::vector<ExrPart>& parts)
{
    const std::string bytes = encode_exr(width, height, parts);
    detail::replace_file_atomically(path, [&](const std::filesystem::path& tmp) { detail::write_bytes(tmp, bytes, path); });
}

std::vector<std::uint32_t> float_bits(const std::vector<float>& values)
{
    std::vector<std::uint32_t> bits(values.size());
    std::memcpy(bits.data(), values.data(), values.size() * sizeof(float));
    return bits;
}

}  // namespace gc
