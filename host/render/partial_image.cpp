#include "host/render/partial_image.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "host/image/exr_writer.h"
#include "host/util/error.h"

#ifndef GC_VERSION
#define GC_VERSION "unknown"
#endif

namespace gc {
namespace {

static_assert(std::endian::native == std::endian::little, "the EXR code reads the file's bytes as the host's");

constexpr std::int32_t k_uint = 0;
constexpr std::int32_t k_float = 2;

// "4" for a chunk, "0-5" for a folded run of chunks.
std::string chunk_id(const PartialChunk& c)
{
    const std::string first = std::to_string(c.range.index);
    return c.folded_chunks > 1 ? first + "-" + std::to_string(c.last_index()) : first;
}

std::string chunk_list(const PartialImage& image)
{
    std::string out;
    for (const PartialChunk& c : image.chunks) out += (out.empty() ? "" : ",") + chunk_id(c);
    return out;
}

// Reading: bounds-checked cursor over the file's bytes; every failure names what was wrong.
class Reader {
public:
    Reader(const std::string& bytes, const std::filesystem::path& path) : m_bytes(bytes), m_path(path) {}

    [[noreturn]] void fail(const std::string& why) const
    {
        throw InputError("partial image '" + m_path.string() + "': " + why);
    }
    void need(std::size_t n, const char* what) const
    {
        if (m_pos + n > m_bytes.size()) fail(std::string("truncated (the file ends inside ") + what + ")");
    }
    template <class T>
    T value(const char* what)
    {
        need(sizeof(T), what);
        T v;
        std::memcpy(&v, m_bytes.data() + m_pos, sizeof v);
        m_pos += sizeof v;
        return v;
    }
    std::string text0(const char* what)
    {
        const std::size_t end = m_bytes.find('\0', m_pos);
        if (end == std::string::npos || end - m_pos > 255) fail(std::string("truncated or corrupt ") + what);
        std::string s = m_bytes.substr(m_pos, end - m_pos);
        m_pos = end + 1;
        return s;
    }
    std::string bytes(std::size_t n, const char* what)
    {
        need(n, what);
        std::string s = m_bytes.substr(m_pos, n);
        m_pos += n;
        return s;
    }
    std::size_t pos() const { return m_pos; }
    void seek(std::uint64_t p, const char* what)
    {
        if (p > m_bytes.size()) fail(std::string("truncated (") + what + " points past the end of the file)");
        m_pos = static_cast<std::size_t>(p);
    }

private:
    const std::string& m_bytes;
    const std::filesystem::path& m_path;
    std::size_t m_pos = 0;
};

std::uint32_t parse_uint(const Reader& r, const std::string& what, const std::string& text)
{
    if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos)
        r.fail(what + " '" + text + "' is not a number");
    const unsigned long long v = std::stoull(text);
    if (v > 0xffffffffull) r.fail(what + " '" + text + "' is out of range");
    return static_cast<std::uint32_t>(v);
}

}  // namespace

void write_partial_image(const std::filesystem::path& path, const PartialImage& image)
{
    ExrPart part;
    for (const PartialChunk& c : image.chunks) {
        const std::string layer = "chunk" + chunk_id(c) + ".";
        const char* names[3] = {"R", "G", "B"};
        for (int k = 0; k < 3; ++k) {
            ExrChannel channel{layer + names[k], ExrPixelType::Float, {}};
            channel.bits.reserve(c.sums.sums.size());
            for (const glm::vec4& v : c.sums.sums) channel.bits.push_back(std::bit_cast<std::uint32_t>(v[k]));
            part.channels.push_back(std::move(channel));
        }
        part.channels.push_back({layer + "N", ExrPixelType::Uint, c.sums.sample_counts});
    }
    part.text = {{"Software", image.software.empty() ? "geocold-cl " GC_VERSION : image.software},
                 {"geocold:partial", "1"},
                 {"geocold:scene_hash", image.scene_hash},
                 {"geocold:options_hash", image.options_hash},
                 {"geocold:seed", std::to_string(image.seed)},
                 {"geocold:chunk_samples", std::to_string(image.chunk_samples)},
                 {"geocold:sample_range", std::to_string(image.first_sample) + ":" + std::to_string(image.end_sample)},
                 {"geocold:chunks", chunk_list(image)},
                 {"geocold:device", image.device},
                 {"geocold:integrator", image.integrator},
                 {"geocold:scene", image.scene}};
    write_exr(path, image.width, image.height, {part});
}

PartialImage read_partial_image(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read partial image '" + path.string() + "': " + std::strerror(errno));
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Reader r(bytes, path);
    if (bytes.size() < 8 || r.value<std::uint32_t>("the magic number") != 20000630u)
        r.fail("not an OpenEXR file");
    const std::uint32_t version = r.value<std::uint32_t>("the version");
    if ((version & 0xff) != 2 || (version & ~0x4ffu) != 0)
        r.fail("not a single-part scan-line OpenEXR 2 file (version field " + std::to_string(version) + ")");

    std::map<std::string, std::string> strings;
    std::map<std::string, std::pair<std::int32_t, std::uint8_t>> channel_types;  // name -> type, order
    std::vector<std::string> channel_order;
    bool have_window = false, have_channels = false;
    std::int32_t window[4] = {};
    std::uint8_t compression = 255;
    for (;;) {
        const std::string name = r.text0("header");
        if (name.empty()) break;
        const std::string type = r.text0("header");
        const std::int32_t size = r.value<std::int32_t>("header");
        if (size < 0) r.fail("corrupt header (attribute '" + name + "' has a negative size)");
        const std::string data = r.bytes(std::size_t(size), "the header");
        if (name == "channels" && type == "chlist") {
            have_channels = true;
            std::size_t p = 0;
            for (;;) {
                const std::size_t end = data.find('\0', p);
                if (end == std::string::npos) r.fail("corrupt channel list");
                const std::string ch = data.substr(p, end - p);
                p = end + 1;
                if (ch.empty()) break;
                if (p + 16 > data.size()) r.fail("corrupt channel list");
                std::int32_t t, xs, ys;
                std::memcpy(&t, data.data() + p, 4);
                std::memcpy(&xs, data.data() + p + 8, 4);
                std::memcpy(&ys, data.data() + p + 12, 4);
                p += 16;
                if (xs != 1 || ys != 1) r.fail("channel '" + ch + "' is subsampled");
                if (t != k_uint && t != k_float && t != 1) r.fail("channel '" + ch + "' has an unknown pixel type");
                channel_types[ch] = {t, 0};
                channel_order.push_back(ch);
            }
        } else if (name == "dataWindow" && type == "box2i" && size == 16) {
            std::memcpy(window, data.data(), 16);
            have_window = true;
        } else if (name == "compression" && size == 1) {
            compression = std::uint8_t(data[0]);
        } else if (type == "string") {
            strings[name] = data;
        }
    }
    if (!have_channels || !have_window) r.fail("not a valid OpenEXR file (no channel list or data window)");
    if (compression != 0)
        r.fail("it is compressed (EXR compression " + std::to_string(compression) +
               "); partial images are written uncompressed by geocold-cl --samples, and only those merge");
    if (window[0] != 0 || window[1] != 0 || window[2] < 0 || window[3] < 0 || window[2] >= 65536 || window[3] >= 65536)
        r.fail("unexpected data window");
    const auto attribute = [&](const std::string& key) -> const std::string& {
        const auto it = strings.find(key);
        if (it == strings.end())
            r.fail("attribute '" + key + "' is missing (not a partial image written by geocold-cl --samples)");
        return it->second;
    };

    PartialImage image;
    image.width = std::uint32_t(window[2] + 1);
    image.height = std::uint32_t(window[3] + 1);
    if (attribute("geocold:partial") != "1") r.fail("geocold:partial is not 1");
    image.scene_hash = attribute("geocold:scene_hash");
    image.options_hash = attribute("geocold:options_hash");
    image.seed = parse_uint(r, "geocold:seed", attribute("geocold:seed"));
    image.chunk_samples = parse_uint(r, "geocold:chunk_samples", attribute("geocold:chunk_samples"));
    if (image.chunk_samples == 0) r.fail("geocold:chunk_samples is 0");
    const std::string& range = attribute("geocold:sample_range");
    const std::size_t colon = range.find(':');
    if (colon == std::string::npos) r.fail("geocold:sample_range '" + range + "' is not A:B");
    image.first_sample = parse_uint(r, "the sample range's start", range.substr(0, colon));
    image.end_sample = parse_uint(r, "the sample range's end", range.substr(colon + 1));
    if (image.end_sample <= image.first_sample || image.first_sample % image.chunk_samples != 0)
        r.fail("geocold:sample_range '" + range + "' is empty or does not start a chunk");
    image.device = strings["geocold:device"];
    image.integrator = strings["geocold:integrator"];
    image.scene = strings["geocold:scene"];
    image.software = strings["Software"];
    const ChunkPlan plan{image.first_sample, image.end_sample, image.chunk_samples};

    // The chunks the file says it holds, each with its four channels.
    const std::string& list = attribute("geocold:chunks");
    std::map<std::string, std::pair<std::size_t, int>> wanted;  // channel -> chunk, component
    std::size_t p = 0;
    while (p < list.size()) {
        std::size_t comma = list.find(',', p);
        if (comma == std::string::npos) comma = list.size();
        const std::string id = list.substr(p, comma - p);
        p = comma + 1;
        const std::size_t dash = id.find('-');
        const std::uint32_t index = parse_uint(r, "a chunk id", id.substr(0, dash));
        const std::uint32_t last = dash == std::string::npos ? index : parse_uint(r, "a chunk id", id.substr(dash + 1));
        for (const std::uint32_t i : {index, last})
            if (i < plan.first_chunk() || i - plan.first_chunk() >= plan.chunk_count())
                r.fail("chunk " + std::to_string(i) + " lies outside its sample range " + range);
        if (!image.chunks.empty() && index <= image.chunks.back().last_index())
            r.fail("geocold:chunks is not in increasing order");
        PartialChunk c;
        c.range = plan.chunk(index - plan.first_chunk());
        if (dash != std::string::npos) {
            const ChunkRange end = plan.chunk(last - plan.first_chunk());
            if (index != 0 || last <= index || end.count != image.chunk_samples)
                r.fail("the folded chunks '" + id + "' do not run from chunk 0 over whole chunks");
            c.range.count = end.end() - c.range.first;
            c.folded_chunks = last - index + 1;
        }
        c.sums.width = image.width;
        c.sums.height = image.height;
        const std::size_t pixels = std::size_t(image.width) * image.height;
        c.sums.sums.assign(pixels, glm::vec4(0.0f));
        c.sums.sample_counts.assign(pixels, 0);
        const std::string layer = "chunk" + id + ".";
        const char* names[4] = {"R", "G", "B", "N"};
        for (int k = 0; k < 4; ++k) {
            const auto it = channel_types.find(layer + names[k]);
            if (it == channel_types.end()) r.fail("channel '" + layer + names[k] + "' is missing");
            if (it->second.first != (k < 3 ? k_float : k_uint))
                r.fail("channel '" + layer + names[k] + "' is " + (k < 3 ? "not FLOAT" : "not UINT"));
            wanted[layer + names[k]] = {image.chunks.size(), k};
        }
        image.chunks.push_back(std::move(c));
    }
    if (image.chunks.empty()) r.fail("it holds no chunks");

    std::size_t line_bytes = 0;
    for (const std::string& ch : channel_order) line_bytes += std::size_t(image.width) * (channel_types[ch].first == 1 ? 2 : 4);
    std::vector<std::uint64_t> offsets(image.height);
    for (auto& o : offsets) o = r.value<std::uint64_t>("the line offset table");
    for (std::uint32_t y = 0; y < image.height; ++y) {
        r.seek(offsets[y], "a line offset");
        const std::int32_t line = r.value<std::int32_t>("a scan line");
        const std::int32_t size = r.value<std::int32_t>("a scan line");
        if (line != std::int32_t(y) || size < 0 || std::size_t(size) != line_bytes)
            r.fail("scan line " + std::to_string(y) + " is corrupt");
        const std::string data = r.bytes(line_bytes, "the pixels");
        std::size_t q = 0;
        for (const std::string& ch : channel_order) {
            const std::size_t each = channel_types[ch].first == 1 ? 2 : 4;
            const auto it = wanted.find(ch);
            if (it != wanted.end()) {
                FilmSums& s = image.chunks[it->second.first].sums;
                const int k = it->second.second;
                for (std::uint32_t x = 0; x < image.width; ++x) {
                    const std::size_t i = std::size_t(y) * image.width + x;
                    if (k < 3) std::memcpy(&s.sums[i][k], data.data() + q + 4 * x, 4);
                    else std::memcpy(&s.sample_counts[i], data.data() + q + 4 * x, 4);
                }
            }
            q += each * image.width;
        }
    }
    for (PartialChunk& c : image.chunks)
        for (std::size_t i = 0; i < c.sums.sums.size(); ++i) {
            if (c.sums.sample_counts[i] > c.range.count)
                r.fail("chunk " + std::to_string(c.range.index) + " counts more samples than the chunk has");
            c.sums.sums[i].w = static_cast<float>(c.sums.sample_counts[i]);
        }
    return image;
}

namespace {

std::string range_text(std::uint32_t a, std::uint32_t b) { return std::to_string(a) + ":" + std::to_string(b); }

}  // namespace

std::optional<FrameDifference> frame_difference(const PartialImage& image, const PartialImage& like)
{
    const auto size = [](const PartialImage& p) { return std::to_string(p.width) + "x" + std::to_string(p.height); };
    if (image.width != like.width || image.height != like.height) return FrameDifference{"size", size(image), size(like)};
    if (image.scene_hash != like.scene_hash) return FrameDifference{"scene hash", image.scene_hash, like.scene_hash};
    if (image.options_hash != like.options_hash)
        return FrameDifference{"render-options hash", image.options_hash, like.options_hash};
    if (image.seed != like.seed) return FrameDifference{"seed", std::to_string(image.seed), std::to_string(like.seed)};
    if (image.chunk_samples != like.chunk_samples)
        return FrameDifference{"chunk size", std::to_string(image.chunk_samples), std::to_string(like.chunk_samples)};
    return std::nullopt;
}

MergedFrame merge_partial_images(const std::vector<std::filesystem::path>& paths, std::optional<std::uint32_t> expected_spp)
{
    if (paths.empty()) throw UsageError("merge: no partial images given");
    MergedFrame merged;
    // First pass: every file read and checked, only its header and chunk list kept, so that
    // memory holds one file at a time (a farm's partials together can exceed it).
    std::map<std::uint32_t, std::pair<ChunkRange, std::size_t>> chunks;  // first index -> range, file
    std::map<std::uint32_t, std::size_t> owner;  // every chunk index held -> file
    std::vector<std::size_t> chunks_left(paths.size(), 0);
    for (std::size_t f = 0; f < paths.size(); ++f) {
        PartialImage image = read_partial_image(paths[f]);
        if (f == 0) {
            merged.first = image;
            merged.first.chunks.clear();
        } else {
            if (const auto d = frame_difference(image, merged.first))
                throw InputError("partial image '" + paths[f].string() + "': its " + d->what + " (" + d->mine +
                                 ") differs from that of '" + paths[0].string() + "' (" + d->theirs +
                                 "): the two are not parts of one frame");
        }
        if (std::find(merged.devices.begin(), merged.devices.end(), image.device) == merged.devices.end())
            merged.devices.push_back(image.device);
        for (const PartialChunk& c : image.chunks) {
            for (std::uint32_t i = c.range.index; i <= c.last_index(); ++i) {
                const auto [it, added] = owner.emplace(i, f);
                if (!added) {
                    const ChunkRange one = ChunkPlan{0, c.range.end(), image.chunk_samples}.chunk(i);
                    throw IncompleteError("partial images '" + paths[it->second].string() + "' and '" +
                                          paths[f].string() + "' overlap: both hold chunk " + std::to_string(i) +
                                          " (samples " + range_text(one.first, one.end()) + ")");
                }
            }
            chunks.emplace(c.range.index, std::make_pair(c.range, f));
            ++chunks_left[f];
        }
    }

    // Coverage: [0, end) without gaps, chunk by chunk.
    const std::uint32_t size = merged.first.chunk_samples;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> missing;
    const auto gap = [&](std::uint32_t a, std::uint32_t b) {
        if (a >= b) return;
        if (!missing.empty() && missing.back().second == a) missing.back().second = b;
        else missing.emplace_back(a, b);
    };
    std::uint32_t covered = 0;  // samples [0, covered) are in
    for (auto it = chunks.begin(); it != chunks.end(); ++it) {
        const ChunkRange& c = it->second.first;
        gap(covered, c.first);
        covered = c.end();
        if (c.count < size && std::next(it) != chunks.end()) {  // a range's short end, not the frame's
            gap(c.end(), (c.index + 1) * size);
            covered = (c.index + 1) * size;
        }
    }
    if (expected_spp) {
        if (covered > *expected_spp)
            throw IncompleteError("the partial images hold samples up to " + std::to_string(covered) + ", past --spp " +
                                  std::to_string(*expected_spp));
        gap(covered, *expected_spp);
    }
    if (!missing.empty()) {
        std::string list;
        for (const auto& [a, b] : missing) list += (list.empty() ? "" : ", ") + range_text(a, b);
        throw IncompleteError("the partial images leave samples missing: " + list +
                              " (render them with --samples A:B, then merge again)");
    }

    // Second pass: the chunks in chunk order, each file read again when its first chunk is due
    // and dropped after its last.
    std::map<std::size_t, PartialImage> open;
    bool started = false;
    for (const auto& [index, entry] : chunks) {
        const std::size_t f = entry.second;
        auto file = open.find(f);
        if (file == open.end()) {
            file = open.emplace(f, read_partial_image(paths[f])).first;
            const PartialImage& again = file->second;
            if (frame_difference(again, merged.first))
                throw InputError("partial image '" + paths[f].string() + "' changed while it was being merged");
        }
        PartialChunk* chunk = nullptr;
        for (PartialChunk& c : file->second.chunks)
            if (c.range.index == index) chunk = &c;
        if (!chunk) throw InputError("partial image '" + paths[f].string() + "' changed while it was being merged");
        if (!started) {
            merged.sums = std::move(chunk->sums);
            started = true;
        } else {
            add_sums(merged.sums, chunk->sums);
        }
        chunk->sums = FilmSums{};
        merged.spp = entry.first.end();
        if (--chunks_left[f] == 0) open.erase(file);
    }
    return merged;
}

}  // namespace gc
