#include "host/render/resumable_frame.h"

#include <chrono>
#include <utility>

#include "host/util/error.h"

namespace gc {

std::uint32_t FrameCheckpoint::samples(std::uint32_t chunk_samples) const
{
    return whole_chunks * chunk_samples + (tail ? tail->range.count : 0);
}

std::vector<PartialChunk> FrameCheckpoint::partial_chunks(std::uint32_t chunk_samples) const
{
    std::vector<PartialChunk> out;
    if (whole_chunks > 0) {
        PartialChunk run{ChunkRange{0, 0, whole_chunks * chunk_samples}, prefix, whole_chunks};
        run.sums.squares.clear();  // partial images keep none
        out.push_back(std::move(run));
    }
    if (tail) {
        out.push_back(*tail);
        out.back().sums.squares.clear();
    }
    return out;
}

FilmSums FrameCheckpoint::frame() const
{
    FilmSums sums = whole_chunks > 0 ? prefix : (tail ? tail->sums : FilmSums{});
    sums.squares.clear();
    if (whole_chunks > 0 && tail) {
        FilmSums last = tail->sums;
        last.squares.clear();
        add_sums(sums, last);
    }
    return sums;
}

FrameStart frame_start_from(const PartialImage& part, const ChunkPlan& plan, const std::filesystem::path& file)
{
    const std::string name = "--resume '" + file.string() + "': ";
    FrameStart start;
    for (const PartialChunk& c : part.chunks) {
        if (c.range.index != start.chunks) break;                               // a gap
        if (c.range.count != c.folded_chunks * part.chunk_samples) break;      // a short chunk
        if (c.range.end() > plan.end_sample) {
            if (c.folded_chunks > 1)
                throw InputError(name + "it holds its first " + std::to_string(c.range.end()) +
                                 " samples added together, more than the " + std::to_string(plan.end_sample) +
                                 " this render asks for: resume it with --spp " + std::to_string(c.range.end()) +
                                 " or more");
            break;
        }
        if (start.chunks == 0) start.sums = c.sums;
        else add_sums(start.sums, c.sums);
        start.chunks += c.folded_chunks;
    }
    if (start.chunks == 0)
        throw InputError(name + "it holds no whole chunk from sample 0 on (sample range " +
                         std::to_string(part.first_sample) + ":" + std::to_string(part.end_sample) +
                         "): nothing to go on from");
    return start;
}

ResumedFrame render_frame_from(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                               const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                               const FrameControl& control, FrameStart start, const Checkpointing& checkpoints)
{
    using Clock = std::chrono::steady_clock;
    if (plan.first_sample != 0) throw UsageError("a resumable frame starts at sample 0");
    FrameAccumulator frame(plan);
    const std::uint32_t resumed = start.chunks * plan.chunk_samples;
    if (start.chunks > 0) frame.start_with(std::move(start.sums), start.chunks);

    // The plan's short last chunk waits outside the frame until the end: a checkpoint holds
    // whole chunks folded, and a resume to more samples renders that chunk whole.
    std::optional<PartialChunk> tail;
    const auto checkpoint = [&] {
        FrameCheckpoint c;
        c.prefix = frame.folded(&c.whole_chunks);
        if (tail && tail->range.index == c.whole_chunks) c.tail = tail;
        return c;
    };
    auto last_checkpoint = Clock::now();
    ResumedFrame out;
    if (resumed < plan.end_sample) {
        const ChunkPlan rest = ChunkPlan::for_range(resumed, plan.end_sample, plan.chunk_samples);
        FrameControl rest_control = control;  // progress over the whole frame, resumed samples included
        if (control.on_progress) rest_control.on_progress = [&](std::uint64_t done) { control.on_progress(resumed + done); };
        out.frame.outcome = render_chunks(
            devices, prepared, settings, setup, rest, rest_control,
            [&](const ChunkRange& range, FilmSums&& sums, bool complete) {
                if (!complete) return frame.add_truncated(range, std::move(sums));
                if (range.count < plan.chunk_samples) tail = PartialChunk{range, std::move(sums)};
                else frame.add(range, std::move(sums));
                const auto now = Clock::now();
                if (checkpoints.write && checkpoints.every_seconds > 0 &&
                    std::chrono::duration<double>(now - last_checkpoint).count() >= checkpoints.every_seconds) {
                    checkpoints.write(checkpoint());
                    last_checkpoint = Clock::now();
                }
            });
    }
    out.complete = checkpoint();
    if (tail) frame.add(tail->range, std::move(tail->sums));
    out.frame.sums = frame.finish(&out.frame.end_sample);
    return out;
}

}  // namespace gc
