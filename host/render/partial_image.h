// Partial images: the sums of some chunks of a frame (chunks.h), as an OpenEXR file that
// `geocold-cl merge` adds up into the frame, bit for bit.
//
// The file is a plain single-part, scanline, uncompressed OpenEXR 2 image that any EXR reader
// opens. Per chunk i it holds the layer "chunk<i>": R, G, B (FLOAT, the per-pixel sums of the
// chunk's samples, accumulated in sample order) and N (UINT, the samples per pixel it holds).
// A checkpoint (geocold-cl --checkpoint-every) holds the frame's first chunks 0..k already
// added in chunk order, as one layer "chunk0-<k>" (listed "0-<k>" in geocold:chunks): the frame
// goes on from it with the same bits, and the file is the size of one chunk however many it
// holds. Such a folded run starts at chunk 0 and holds whole chunks only.
// String attributes say where it belongs:
//   geocold:partial        "1"
//   geocold:scene_hash     content of the scene and its files (frame_hash.h), 16 hex digits
//   geocold:options_hash   the image-changing render options, 16 hex digits
//   geocold:seed, geocold:chunk_samples, geocold:sample_range ("A:B"), geocold:chunks ("4,5,6";
//                          a checkpoint's "0-5,6")
//   geocold:device, geocold:integrator, geocold:scene (the file as given), Software (version)
// geocold-cl writes it with its own EXR code (exr_writer.h) and reads it with its own code (no
// OpenImageIO needed, so the bare GPU build writes partials too); writes are atomic: a reader
// sees a whole file or none.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host/render/chunks.h"

namespace gc {

struct PartialChunk {
    ChunkRange range;
    FilmSums sums;  // sums (alpha: the sample count, as float) and sample_counts; no squares
    // Chunks folded into `sums` (range.index .. range.index + folded_chunks - 1, added in chunk
    // order); more than 1 only for a checkpoint's run from chunk 0, whose range spans them all.
    std::uint32_t folded_chunks = 1;
    std::uint32_t last_index() const { return range.index + folded_chunks - 1; }
};

struct PartialImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::string scene_hash;
    std::string options_hash;
    std::uint32_t seed = 0;
    std::uint32_t chunk_samples = 0;
    std::uint32_t first_sample = 0;  // the sample range the file was asked to hold
    std::uint32_t end_sample = 0;
    std::string device;
    std::string integrator;
    std::string scene;
    std::string software;
    std::vector<PartialChunk> chunks;  // in chunk order
};

// Writes atomically; OutputError naming the file on failure.
void write_partial_image(const std::filesystem::path& path, const PartialImage& image);

// Reads and checks a partial image; InputError naming the file and what is wrong (not an
// EXR, truncated, compressed, a missing attribute or channel, chunks that do not fit the range).
PartialImage read_partial_image(const std::filesystem::path& path);

// The first of the facts that make two partial images parts of one frame (size, scene hash,
// render-options hash, seed, chunk size) on which `image` differs from `like`, with both values.
struct FrameDifference {
    std::string what;    // "size", "scene hash", "render-options hash", "seed", "chunk size"
    std::string mine;    // image's value
    std::string theirs;  // like's value
};
std::optional<FrameDifference> frame_difference(const PartialImage& image, const PartialImage& like);

// The frame from partial images: every input must have the same size, scene hash, options
// hash, seed and chunk size (InputError naming the file that differs), no chunk may be in two
// files (IncompleteError naming both), and together they must cover the samples [0, end)
// without a gap, end being expected_spp when given (IncompleteError listing the missing sample
// ranges). The chunks are added in chunk order: the bits of the frame rendered in one process.
// Each file is read twice (checks, then pixels in chunk order), so memory holds the frame and
// the files whose chunks are being added, not every input at once.
struct MergedFrame {
    FilmSums sums;
    std::uint32_t spp = 0;
    PartialImage first;  // the first input's header (no chunks)
    std::vector<std::string> devices;  // every input's device, without repeats
};
MergedFrame merge_partial_images(const std::vector<std::filesystem::path>& paths,
                                 std::optional<std::uint32_t> expected_spp = std::nullopt);

}  // namespace gc
