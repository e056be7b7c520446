#include "host/app/frame_checkpoints.h"

#include <cstdio>
#include <utility>

#include "host/image/image_io.h"
#include "host/util/error.h"
#include "host/util/log.h"

namespace gc {

std::filesystem::path checkpoint_path(const std::filesystem::path& output)
{
    std::filesystem::path path = output;
    path.replace_extension(".partial.exr");
    return path;
}

FrameCheckpoints::FrameCheckpoints(const Options& options, std::filesystem::path output, PartialImage header,
                                   ImageMetadata meta, DisplayTransform display)
    : m_every_seconds(options.checkpoint_seconds), m_output(std::move(output)), m_partial(checkpoint_path(m_output)),
      m_header(std::move(header)), m_meta(std::move(meta)), m_display(display)
{
    if (m_every_seconds > 0) {
        char every[32];
        std::snprintf(every, sizeof every, "%g", m_every_seconds);
        log_info(std::string("checkpoints every ") + every + " s to " + m_output.string() + " and " + m_partial.string());
    }
    if (options.resume_path.empty()) return;
    const std::filesystem::path file = options.resume_path;
    if (std::filesystem::weakly_canonical(file) == std::filesystem::weakly_canonical(m_output))
        throw UsageError("--resume '" + file.string() + "' is also the output: the render would overwrite it");
    const PartialImage part = read_partial_image(file);
    if (const auto d = frame_difference(part, m_header))
        throw InputError("--resume '" + file.string() + "': its " + d->what + " (" + d->mine +
                         ") differs from this render's (" + d->theirs +
                         "): it is not a part of this frame (only --spp may change)");
    const ChunkPlan plan{0, m_header.end_sample, m_header.chunk_samples};
    m_start = frame_start_from(part, plan, file);
    log_info("resuming from " + file.string() + ": its first " + std::to_string(m_start.chunks * plan.chunk_samples) +
             " of " + std::to_string(plan.end_sample) + " samples");
}

Checkpointing FrameCheckpoints::while_rendering() const
{
    Checkpointing c;
    c.every_seconds = m_every_seconds;
    c.write = [this](const FrameCheckpoint& checkpoint) {
        ImageMetadata meta = m_meta;
        meta.spp = checkpoint.samples(m_header.chunk_samples);
        // A checkpoint that cannot be written (a full disk) leaves the last one whole and the
        // render going: the final write says whether the output can be written at all.
        try {
            write_image(m_output, mean_film(checkpoint.frame()), meta, m_display);
            write_partial(checkpoint, m_header.device);
        } catch (const OutputError& e) {
            log_warning(std::string("checkpoint not written: ") + e.what());
            return;
        }
        log_verbose("checkpoint: " + std::to_string(meta.spp) + " spp in " + m_output.string() + " and " +
                    m_partial.string());
    };
    return c;
}

void FrameCheckpoints::write_final(const FrameCheckpoint& complete, const std::string& devices) const
{
    if (m_every_seconds <= 0) return;
    if (complete.samples(m_header.chunk_samples) == 0) {
        log_info("no chunk was complete: no checkpoint written");
        return;
    }
    write_partial(complete, devices);
    log_info("wrote checkpoint " + m_partial.string() + " (" + std::to_string(complete.samples(m_header.chunk_samples)) +
             " spp; --resume it to render more)");
}

void FrameCheckpoints::write_partial(const FrameCheckpoint& checkpoint, const std::string& devices) const
{
    if (checkpoint.samples(m_header.chunk_samples) == 0) return;
    PartialImage part = m_header;
    part.device = devices;
    part.chunks = checkpoint.partial_chunks(m_header.chunk_samples);
    write_partial_image(m_partial, part);
}

}  // namespace gc
