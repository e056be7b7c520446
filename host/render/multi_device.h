// One frame on several OpenCL devices of a machine: a pull-based queue of canonical chunks
// (chunks.h), one host thread per device. Used by geocold-cl (--device all, --samples A:B) and
// open to other front ends.
//
//     FrameResult frame = render_frame(devices, prepared, settings, setup,
//                                      ChunkPlan::for_range(0, spp, 64), control);
//     write_image("out.exr", mean_film(frame.sums), meta);
//
// Each device gets a Session of its own (context, device scene, renderer), built in its thread,
// so the kernels of several devices compile at once; rendering starts when every device is set
// up (or failed), so that no device renders on the cores another one's set-up needs. A device
// pulls the next chunks off the queue (a GPU takes more at a time than a CPU, ask_size()),
// renders each from a cleared film and hands its sums on. When the queue is empty, an idle
// device re-renders the chunk another device has held longest, if it expects to finish it
// sooner (a backup, as MapReduce's backup tasks): the first copy in wins and the other is
// abandoned at its next pass. On devices of one kind the copies have the same bits; across
// kinds they agree within --consistency's tolerance, which is then all a frame rendered on
// mixed devices promises.
//
// A device that fails (its driver, its memory) drops out with a warning; its chunks go back to
// the queue. The frame fails only when no device is left. A device far slower than the others
// leaves the frame once its second pass shows it (adds_too_little), its chunk going back to the
// queue; a CPU device beside others probes its rate on a few pixels first and may leave before
// it takes a chunk.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "host/cl/device.h"
#include "host/render/chunks.h"
#include "host/render/render_settings.h"
#include "host/render/render_setup.h"
#include "host/render/session.h"

namespace gc {

struct FrameControl {
    double time_limit_seconds = 0.0;  // from the start of rendering (after the kernels are built); 0: none
    std::function<bool()> cancelled;  // asked between passes; true stops every device
    // Called (from any device's thread, one call at a time) after each pass with the samples
    // per pixel finished so far over the whole plan (complete chunks and chunks in flight).
    std::function<void(std::uint64_t samples_done)> on_progress;
    // Called from a device's thread once its set-up is done (with its index in the device
    // list), before it waits for the others' and rendering starts.
    std::function<void(std::size_t device)> on_device_ready;
    // Whether the chunks' sums carry the squares too (for the variance; twice the read-back).
    bool with_squares = false;
};

struct DeviceReport {
    std::string name;           // "<device> (<platform>)"
    bool is_gpu = false;
    std::uint32_t chunks = 0;   // chunks it delivered first
    std::uint32_t backups = 0;  // of those, backups of a chunk another device held
    std::uint64_t samples = 0;  // samples per pixel it rendered (including abandoned work)
    double setup_seconds = 0;   // upload and kernel build
    double ready_at = 0;        // seconds from the call to the end of its set-up (on_device_ready's return)
    double busy_seconds = 0;    // rendering
    double probe_seconds = 0;   // a CPU device's probe of its rate before its first chunk
    double probe_rate = 0;      // ... and the rate it found, in samples of every pixel per second
    double finished_at = 0;     // seconds from the frame's start to the device's last chunk
    std::string failure;        // why it dropped out; empty if it did not
    bool left_slow = false;     // left the frame as too slow to help (adds_too_little)
};

struct FrameOutcome {
    bool cancelled = false;
    bool timed_out = false;
    double seconds = 0.0;  // from the start of rendering (every device set up) to the last chunk in the sink
    double seconds_with_setup = 0.0;  // from the call to the last chunk in the sink, the set-ups included
    double cleanup_seconds = 0.0;     // from the last chunk in the sink to the return (the devices released)
    std::vector<DeviceReport> devices;
};

// Called from the devices' threads, one call at a time, for each chunk as it completes (its
// sums and sample counts; squares only with FrameControl::with_squares or in a frame in
// rounds, since they double the read-back); and,
// at a cancel or a deadline, for each chunk in flight with the samples it got (complete = false,
// range.count cut to them; never for a chunk with none).
using ChunkSink = std::function<void(const ChunkRange& range, FilmSums&& sums, bool complete)>;

// A frame rendered in rounds (adaptive sampling, adaptive.h). Each check point (a sample count
// inside the plan, a multiple of its chunk size, ascending) ends a round; the next round is
// queued once every chunk before its check point has reached the sink, and renders only the
// pixels `pixels_after(check point)` picks then (strictly ascending indices; an empty pick ends
// the frame there). Devices wait at each check point: the picks depend on every earlier chunk.
// The chunks of a frame in rounds carry their squares, which the picks need.
struct ChunkRounds {
    std::vector<std::uint32_t> check_points;
    std::function<std::vector<std::uint32_t>(std::uint32_t check_point)> pixels_after;
    bool active() const { return static_cast<bool>(pixels_after); }
};

// How many chunks a device asks for at a time: 1 for a CPU; for a GPU, a quarter of its fair
// share of what is left, at most 8.
std::uint32_t ask_size(bool is_gpu, std::uint32_t chunks_left, std::uint32_t device_count);

// What an idle device knows of another device's running chunk, for deciding on a backup.
struct RunningChunk {
    std::uint32_t count = 0;            // samples in the chunk
    std::uint32_t done = 0;             // of those, finished by its holder so far
    double elapsed_seconds = 0.0;       // since its holder started it
    double holder_seconds_per_sample = 0.0;  // the holder's measured rate; 0 before its first chunk
};

// Seconds a backup of `chunk` on a device rendering `mine_seconds_per_sample` would save: the
// holder's expected time left less this device's time for the whole chunk; 0 when that is
// not more than a quarter of the holder's time left, or when this device's rate is not known
// yet. Before the holder has a measured
// rate, its chunk tells: elapsed / done per sample, or, while not even one pass is done, as
// long again as it has taken so far (so a slow device's first chunk is backed up too).
double backup_gain(double mine_seconds_per_sample, const RunningChunk& chunk);

// Whether a device that renders `mine` samples per second should leave a frame the other
// devices render at `others` samples per second together: when it would add under a tenth of
// their rate. Driving a GPU takes host threads, and a CPU device busy on every other core slows
// them: on the H200 machine by more than PoCL added (docs/performance.md, "Several devices on
// one frame"). False while either rate is unknown (0).
bool adds_too_little(double mine, double others);

// Renders every chunk of `plan` (until `control` stops it, or `rounds` ends it early) on
// `devices`, handing each to `sink`. Throws the first device's error when every device failed,
// and UsageError for check points that do not fit the plan.
FrameOutcome render_chunks(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                           const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                           const FrameControl& control, const ChunkSink& sink, const ChunkRounds& rounds = {});

struct FrameResult {
    FilmSums sums;               // the frame: chunks added in chunk order
    std::uint32_t end_sample = 0;  // the frame holds samples [plan.first_sample, end_sample)
    FrameOutcome outcome;
};

// ChunkRounds whose picks look at the frame so far: every chunk before the check point, added
// in chunk order, squares included.
struct FrameRounds {
    std::vector<std::uint32_t> check_points;
    std::function<std::vector<std::uint32_t>(const FilmSums& frame, std::uint32_t check_point)> pixels_after;
};

// render_chunks, with the chunks added into the frame in chunk order. After a cancel or a
// deadline the frame holds the longest prefix of the plan that was rendered; after rounds that
// picked no pixel, the frame up to that check point.
FrameResult render_frame(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                         const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                         const FrameControl& control, const FrameRounds& rounds = {});

}  // namespace gc
