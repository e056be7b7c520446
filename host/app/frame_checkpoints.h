// geocold-cl --resume and --checkpoint-every: the file a render goes on from (read and checked
// before any rendering), and the files each checkpoint writes: the output with the frame so
// far, and beside it the partial image of its complete chunks (checkpoint_path), which
// --resume takes. Both are replaced atomically, so a kill leaves the last checkpoint whole.
#pragma once

#include <filesystem>
#include <string>

#include "host/app/options.h"
#include "host/image/display_transform.h"
#include "host/image/film.h"
#include "host/render/resumable_frame.h"

namespace gc {

// "<output without its extension>.partial.exr", beside the output.
std::filesystem::path checkpoint_path(const std::filesystem::path& output);

class FrameCheckpoints {
public:
    // `header`: the partial-image header of this render's frame (partial_header.h). Reads
    // options.resume_path, if any, and checks it belongs to this frame: InputError naming the
    // file and what differs.
    FrameCheckpoints(const Options& options, std::filesystem::path output, PartialImage header, ImageMetadata meta,
                     DisplayTransform display);

    // Where the frame starts: the resumed chunks, or nothing. Once.
    FrameStart take_start() { return std::move(m_start); }
    // For render_frame_from: the checkpoints while rendering.
    Checkpointing while_rendering() const;
    // After the render (finished, stopped or interrupted), with --checkpoint-every: the partial
    // image of the complete chunks; `devices` those that rendered them.
    void write_final(const FrameCheckpoint& complete, const std::string& devices) const;

private:
    void write_partial(const FrameCheckpoint& checkpoint, const std::string& devices) const;

    double m_every_seconds;
    std::filesystem::path m_output;
    std::filesystem::path m_partial;
    PartialImage m_header;
    ImageMetadata m_meta;
    DisplayTransform m_display;
    FrameStart m_start;
};

}  // namespace gc
