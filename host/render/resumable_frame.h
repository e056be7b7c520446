// A frame that goes on from a checkpoint and leaves checkpoints as it goes (geocold-cl
// --resume, --checkpoint-every), with the bits of the frame rendered in one go.
//
// A checkpoint is what the frame holds of complete chunks: chunks 0..k-1, whole, added in
// chunk order (FrameAccumulator's prefix), plus the plan's short last chunk when it follows
// them. Since the frame is ((c0 + c1) + c2) + ..., that prefix is all a later render needs to go
// on to any larger spp of the same chunk size: it adds chunks k, k+1, ... to it in order. A
// partial image from --samples 0:B serves too (its chunks are folded in order on reading).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

#include "host/render/multi_device.h"
#include "host/render/partial_image.h"

namespace gc {

// The frame's first chunks, added in chunk order.
struct FrameStart {
    FilmSums sums;
    std::uint32_t chunks = 0;  // 0: the frame starts from nothing
};

struct FrameCheckpoint {
    FilmSums prefix;                  // chunks 0 .. whole_chunks - 1, folded (no squares)
    std::uint32_t whole_chunks = 0;
    std::optional<PartialChunk> tail; // the plan's short last chunk, when it follows the prefix

    // Samples the checkpoint holds, [0, samples()).
    std::uint32_t samples(std::uint32_t chunk_samples) const;
    // The checkpoint as a partial image's chunks: one folded run (or one chunk), then the tail.
    std::vector<PartialChunk> partial_chunks(std::uint32_t chunk_samples) const;
    // The frame it holds (the prefix plus the tail): the bits of a frame of samples() samples.
    FilmSums frame() const;
};

// The whole chunks from chunk 0 on that `part` holds and the frame of `plan` (which starts at
// sample 0) has too, folded in chunk order. A short chunk and anything after a gap are left
// out (rendered again). InputError naming `file` when `part` holds none, or holds a folded run
// longer than the frame.
FrameStart frame_start_from(const PartialImage& part, const ChunkPlan& plan, const std::filesystem::path& file);

struct Checkpointing {
    double every_seconds = 0.0;  // 0: no checkpoints while rendering
    // Called from a device's thread (one call at a time) when a chunk completes at least
    // every_seconds after the last call.
    std::function<void(const FrameCheckpoint&)> write;
};

struct ResumedFrame {
    FrameResult frame;        // as render_frame's, including a stopped chunk's samples
    FrameCheckpoint complete; // the complete chunks at the end: what a resume can go on from
};

// render_frame from `start` over the rest of `plan` (which must start at sample 0), writing
// checkpoints on the way.
ResumedFrame render_frame_from(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                               const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                               const FrameControl& control, FrameStart start, const Checkpointing& checkpoints);

}  // namespace gc
