#include "host/render/multi_device.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "host/render/chunk_handoff.h"
#include "host/render/pass_planner.h"
#include "host/util/error.h"
#include "host/util/log.h"

namespace gc {
namespace {

using Clock = std::chrono::steady_clock;

// About how many pixels a CPU device's probe renders (Renderer::estimate_seconds_per_sample):
// a thirty-second of them at 1024x1024, every one up to about 181x181.
constexpr std::uint32_t kProbePixels = 1u << 15;

double seconds_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// The chunk numbers that end each round: one per check point, then the plan's end.
std::vector<std::uint32_t> round_ends(const ChunkPlan& plan, const ChunkRounds& rounds)
{
    std::vector<std::uint32_t> ends;
    for (std::uint32_t point : rounds.check_points) {
        if (point <= plan.first_sample || point >= plan.end_sample || point % plan.chunk_samples != 0 ||
            (!ends.empty() && point <= plan.first_sample + ends.back() * plan.chunk_samples))
            throw UsageError("check point " + std::to_string(point) + " is not an ascending chunk boundary inside " +
                             std::to_string(plan.first_sample) + ":" + std::to_string(plan.end_sample));
        ends.push_back((point - plan.first_sample) / plan.chunk_samples);
    }
    ends.push_back(plan.chunk_count());
    return ends;
}

// What every device's thread shares. Chunks are named by their number n in the plan.
struct Shared {
    Shared(const ChunkPlan& plan_, std::size_t devices, const ChunkRounds& rounds_)
        : plan(plan_),
          rounds(rounds_),
          ends(round_ends(plan_, rounds_)),
          finished(plan_.chunk_count()),
          progress(devices),
          chunk_started(devices),
          seconds_per_sample(devices),
          pass_rate(devices)
    {
        for (std::uint32_t n = 0; n < ends.front(); ++n) todo.push_back(n);
        for (auto& p : progress) p = 0;
        for (auto& t : chunk_started) t = 0.0;
        for (auto& s : seconds_per_sample) s = 0.0;
        for (auto& r : pass_rate) r = 0.0;
        reserved.resize(devices);
    }

    const ChunkPlan plan;
    const ChunkRounds& rounds;
    const std::vector<std::uint32_t> ends;  // round_ends
    std::mutex mutex;
    std::condition_variable changed;
    std::deque<std::uint32_t> todo;                       // not yet taken, in order
    std::vector<std::deque<std::uint32_t>> reserved;      // taken by a device, not yet started
    std::map<std::uint32_t, std::set<std::size_t>> running;  // started, by which devices
    std::vector<std::atomic<bool>> finished;              // delivered (a copy still running stops)
    std::uint32_t finished_count = 0;
    std::size_t round = 0;  // the round queued last
    bool rounds_over = false;  // a pick left no pixel: no more rounds
    std::shared_ptr<const std::vector<std::uint32_t>> pixels;  // the round's pick; null: every pixel
    std::uint32_t sunk_count = 0;  // complete chunks through the sink (under sink_mutex)
    std::optional<Clock::time_point> last_sunk;  // the sink's last return (under sink_mutex)
    std::exception_ptr round_error;  // a pick that threw: the frame stops and render_chunks rethrows it
    std::vector<std::atomic<std::uint32_t>> progress;     // samples of its current chunk, per device
    std::vector<std::atomic<double>> chunk_started;       // when it started its current chunk (frame seconds)
    std::vector<std::atomic<double>> seconds_per_sample;  // per device, 0 = not known yet
    std::vector<std::atomic<double>> pass_rate;  // samples per second of its last pass; 0: unknown or gone
    std::atomic<bool> stop{false};
    bool cancelled = false;
    bool timed_out = false;
    std::size_t live = 0;
    std::size_t setting_up = 0;  // devices whose set-up has neither finished nor failed
    std::optional<Clock::time_point> start;  // every device set up (or failed): rendering begins
    std::atomic<std::uint64_t> complete_samples{0};

    std::mutex sink_mutex;      // one sink call at a time
    std::mutex progress_mutex;  // one on_progress call at a time

    // Chunks queued so far end here (a round's end).
    std::uint32_t queued_end() const { return ends[round]; }
    // Whether another round may still be queued (under mutex).
    bool round_pending() const { return !rounds_over && round + 1 < ends.size(); }
    // The other devices' pass rates together.
    double others_rate(std::size_t me) const
    {
        double sum = 0.0;
        for (std::size_t i = 0; i < pass_rate.size(); ++i)
            if (i != me) sum += pass_rate[i].load();
        return sum;
    }
};

// Device `me` leaves the frame (under shared.mutex): its reserved chunks, and those it was
// rendering that no other device holds and none has finished, go back to the queue in order.
void leave_frame(Shared& shared, std::size_t me, const std::vector<std::uint32_t>& mine)
{
    std::vector<std::uint32_t> back(shared.reserved[me].begin(), shared.reserved[me].end());
    shared.reserved[me].clear();
    for (std::uint32_t n : mine) {
        shared.running[n].erase(me);
        if (shared.running[n].empty()) {
            shared.running.erase(n);
            if (!shared.finished[n]) back.push_back(n);
        }
    }
    std::sort(back.begin(), back.end());
    for (auto it = back.rbegin(); it != back.rend(); ++it) shared.todo.push_front(*it);
    shared.pass_rate[me] = 0.0;
    shared.progress[me] = 0;  // its part-done chunk no longer counts towards the frame's progress
    --shared.live;
    shared.changed.notify_all();
}

// After the sink took a complete chunk (under sink_mutex): if that completed the round, pick
// the next round's pixels and queue its chunks.
void start_next_round_if_due(Shared& shared)
{
    {
        std::lock_guard lock(shared.mutex);
        if (shared.sunk_count != shared.queued_end() || !shared.round_pending() || shared.stop) return;
    }
    const std::uint32_t check_point = shared.plan.first_sample + shared.queued_end() * shared.plan.chunk_samples;
    std::shared_ptr<const std::vector<std::uint32_t>> pixels;
    try {
        pixels = std::make_shared<const std::vector<std::uint32_t>>(shared.rounds.pixels_after(check_point));
    } catch (...) {
        // Not a device's failure: every device would wait for a round that never comes.
        std::lock_guard lock(shared.mutex);
        shared.round_error = std::current_exception();
        shared.stop = true;
        shared.changed.notify_all();
        return;
    }
    std::lock_guard lock(shared.mutex);
    if (pixels->empty()) {
        shared.rounds_over = true;
    } else {
        ++shared.round;
        shared.pixels = std::move(pixels);
        for (std::uint32_t n = shared.ends[shared.round - 1]; n < shared.queued_end(); ++n) shared.todo.push_back(n);
    }
    shared.changed.notify_all();
}

}  // namespace

double backup_gain(double mine_seconds_per_sample, const RunningChunk& chunk)
{
    if (!(mine_seconds_per_sample > 0.0) || chunk.count == 0) return 0.0;
    const std::uint32_t done = std::min(chunk.done, chunk.count);
    double left = 0.0;
    if (chunk.holder_seconds_per_sample > 0.0)
        left = chunk.holder_seconds_per_sample * (chunk.count - done);
    else if (done > 0)
        left = chunk.elapsed_seconds / done * (chunk.count - done);
    else
        left = chunk.elapsed_seconds;
    const double gain = left - mine_seconds_per_sample * chunk.count;
    // A backup costs this device the whole chunk: worth it only for a clear saving.
    return gain > 0.25 * left ? gain : 0.0;
}

bool adds_too_little(double mine, double others) { return mine > 0.0 && others > 0.0 && mine < 0.1 * others; }

std::uint32_t ask_size(bool is_gpu, std::uint32_t chunks_left, std::uint32_t device_count)
{
    if (!is_gpu || chunks_left == 0) return 1;
    const std::uint32_t share = chunks_left / std::max(1u, device_count);
    return std::clamp(share / 4, 1u, 8u);
}

namespace {

// What every device of one render_chunks call renders, and for whom.
struct FrameJob {
    const PreparedScene& prepared;
    const RenderSettings& settings;
    const RenderSetup& setup;
    const ChunkPlan& plan;
    const FrameControl& control;
    const ChunkSink& sink;
    const ChunkRounds& rounds;
    Clock::time_point called;  // render_chunks was called
};

// Tells control.on_progress the samples of complete chunks plus every device's part-done one.
void report_progress(const FrameJob& job, Shared& shared)
{
    if (!job.control.on_progress) return;
    std::uint64_t done = shared.complete_samples.load();
    for (const auto& p : shared.progress) done += p.load();
    std::lock_guard lock(shared.progress_mutex);
    job.control.on_progress(std::min<std::uint64_t>(done, job.plan.end_sample - job.plan.first_sample));
}

// A chunk a device took: its number, whether it backs up another device's run of it, and
// the pixels of its round (null: every pixel).
struct Claim {
    std::uint32_t n = 0;
    bool backup = false;
    std::shared_ptr<const std::vector<std::uint32_t>> pixels;
};

// How rendering a claimed chunk ended.
struct ChunkEnd {
    std::uint32_t done = 0;  // samples rendered
    bool abandoned = false;  // another device delivered it first
    bool stopped = false;    // the frame stopped (cancelled, out of time) before it was complete
    bool left = false;       // this device left the frame (adds_too_little)
};

// One device's thread: a session on the device, then chunks claimed from the shared queue,
// rendered and handed to the sink until the plan is done or the frame stops.
class DeviceWorker {
public:
    DeviceWorker(std::size_t me, const cl::DeviceInfo& device, const FrameJob& job, Shared& shared,
                 DeviceReport& report)
        : m_me(me), m_device(device), m_job(job), m_shared(shared), m_report(report)
    {
    }

    // Runs the device's part of the frame; a failure leaves the frame (its chunks go back to
    // the queue) and is returned, also recorded in the report.
    std::exception_ptr run() noexcept
    {
        m_report.name = m_device.device_name + " (" + m_device.platform_name + ")";
        m_report.is_gpu = m_device.is_gpu;
        try {
            const auto setup_start = Clock::now();
            Session session(m_device, m_job.prepared, m_job.settings, m_job.setup);
            Renderer& renderer = session.renderer();
            m_with_squares = m_job.control.with_squares || m_job.rounds.active();
            ChunkHandoff handoff(session.context(), renderer, m_with_squares);
            m_report.setup_seconds = seconds_between(setup_start, Clock::now());
            if (m_job.control.on_device_ready) m_job.control.on_device_ready(m_me);
            m_report.ready_at = seconds_between(m_job.called, Clock::now());
            m_start = wait_for_every_setup();
            render_until_done(renderer, handoff);
            handoff.wait();
            return nullptr;
        } catch (...) {
            std::exception_ptr error = std::current_exception();
            try {
                std::rethrow_exception(error);
            } catch (const std::exception& e) {
                m_report.failure = e.what();
            } catch (...) {
                m_report.failure = "unknown error";
            }
            std::lock_guard lock(m_shared.mutex);
            if (!m_set_up) end_setup();
            leave_frame(m_shared, m_me, m_mine);
            return error;
        }
    }

private:
    double elapsed() const { return seconds_between(m_start, Clock::now()); }

    // Rendering starts once every device is set up (or failed): a device ready early would
    // otherwise render on the cores the others' set-up (a GPU's upload and driver calls) runs
    // on, and slow the frame's fastest device down (docs/performance.md, "Several devices on
    // one frame"). Cycles' multi-device waits for every device's kernels and scene likewise.
    Clock::time_point wait_for_every_setup()
    {
        std::unique_lock lock(m_shared.mutex);
        end_setup();
        m_shared.changed.wait(lock, [this] { return m_shared.setting_up == 0; });
        return *m_shared.start;
    }

    // This device's set-up is over, done or failed (under shared.mutex); the last one starts the frame.
    void end_setup()
    {
        m_set_up = true;
        if (--m_shared.setting_up == 0) {
            m_shared.start = Clock::now();
            m_shared.changed.notify_all();
        }
    }

    void render_until_done(Renderer& renderer, ChunkHandoff& handoff)
    {
        if (probes_first() && !stays_after_probe(renderer)) return;
        while (const std::optional<Claim> claim = next_claim()) {
            const auto chunk_start = Clock::now();
            m_shared.chunk_started[m_me] = seconds_between(m_start, chunk_start);
            const ChunkEnd end = render_chunk(renderer, *claim);
            m_report.busy_seconds += seconds_between(chunk_start, Clock::now());
            m_report.samples += end.done;
            if (end.left) return;
            finish_chunk(renderer, handoff, *claim, end);
            if (end.stopped) return;
        }
    }

    // A CPU device beside others learns its rate from a probe of a few pixels before it takes
    // a chunk: its threads share the host's cores with those that drive the other devices, and
    // learning it from passes over every pixel would hold every core for tenths of a second
    // and delay a GPU's last chunk (docs/performance.md, "Several devices on one frame").
    bool probes_first()
    {
        if (m_device.is_gpu || m_job.settings.integrator != IntegratorKind::Path) return false;
        std::lock_guard lock(m_shared.mutex);
        return m_shared.live > 1;
    }

    // Probes this device's rate, then waits, holding no chunk, until another device's rate is
    // known (or no other is left, or the frame is over), and leaves the frame if it would add
    // too little (adds_too_little). Whether it stays.
    bool stays_after_probe(Renderer& renderer)
    {
        const auto probe_start = Clock::now();
        const double seconds_per_sample = renderer.estimate_seconds_per_sample(kProbePixels);
        m_report.probe_seconds = seconds_between(probe_start, Clock::now());
        if (!(seconds_per_sample > 0.0)) return true;
        m_report.probe_rate = 1.0 / seconds_per_sample;
        m_shared.pass_rate[m_me] = m_report.probe_rate;
        std::unique_lock lock(m_shared.mutex);
        m_shared.changed.notify_all();  // a CPU device waiting on this one's rate
        while (!m_shared.stop && m_shared.live > 1 && !(m_shared.others_rate(m_me) > 0.0) && !plan_done())
            m_shared.changed.wait_for(lock, std::chrono::milliseconds(5));
        if (!adds_too_little(m_shared.pass_rate[m_me].load(), m_shared.others_rate(m_me))) return true;
        m_report.left_slow = true;
        leave_frame(m_shared, m_me, m_mine);
        return false;
    }

    // Whether every chunk is delivered and none will be queued (under shared.mutex).
    bool plan_done() const
    {
        if (!m_shared.running.empty() || !m_shared.todo.empty() || m_shared.round_pending()) return false;
        for (const auto& r : m_shared.reserved)
            if (!r.empty()) return false;
        return true;
    }

    // The next chunk this device renders, or none once the plan is done or the frame stops:
    // its own reserved chunks first (a GPU reserves several at a time), then one another
    // device reserved and has not started, then a backup of a running chunk its holder will
    // finish later than this device could; else it waits for a change.
    std::optional<Claim> next_claim()
    {
        std::unique_lock lock(m_shared.mutex);
        for (;;) {
            if (m_shared.stop) return std::nullopt;
            auto& own = m_shared.reserved[m_me];
            if (own.empty() && !m_shared.todo.empty()) {
                const std::uint32_t want = ask_size(m_device.is_gpu, std::uint32_t(m_shared.todo.size()),
                                                    std::uint32_t(m_shared.live));
                for (std::uint32_t i = 0; i < want && !m_shared.todo.empty(); ++i) {
                    own.push_back(m_shared.todo.front());
                    m_shared.todo.pop_front();
                }
            }
            if (own.empty()) {
                for (auto& other : m_shared.reserved)
                    if (other.size() > 0 && &other != &own) {
                        own.push_back(other.back());
                        other.pop_back();
                        break;
                    }
            }
            std::optional<Claim> claim;
            if (!own.empty()) {
                claim = Claim{own.front(), false, nullptr};
                own.pop_front();
            } else if (const std::optional<std::uint32_t> pick = backup_pick()) {
                claim = Claim{*pick, true, nullptr};
            }
            if (claim) {
                m_shared.running[claim->n].insert(m_me);
                m_mine.push_back(claim->n);
                claim->pixels = m_shared.pixels;
                return claim;
            }
            if (plan_done()) return std::nullopt;
            m_shared.changed.wait_for(lock, std::chrono::milliseconds(20));
        }
    }

    // The running chunk (held by one other device) whose backup gains most (backup_gain), if
    // any gains (under shared.mutex).
    std::optional<std::uint32_t> backup_pick() const
    {
        const double mine_spp = m_shared.seconds_per_sample[m_me].load();
        double best_gain = 0.0;
        std::optional<std::uint32_t> pick;
        for (const auto& [chunk, holders] : m_shared.running) {
            if (holders.size() != 1 || holders.count(m_me)) continue;
            const std::size_t holder = *holders.begin();
            RunningChunk running;
            running.count = m_job.plan.chunk(chunk).count;
            running.done = m_shared.progress[holder].load();
            running.elapsed_seconds = elapsed() - m_shared.chunk_started[holder].load();
            running.holder_seconds_per_sample = m_shared.seconds_per_sample[holder].load();
            const double gain = backup_gain(mine_spp, running);
            if (gain > best_gain) {
                best_gain = gain;
                pick = chunk;
            }
        }
        return pick;
    }

    // Renders the claimed chunk pass by pass until it is complete, another device delivers
    // it, the frame stops, or this device leaves the frame for adding too little.
    ChunkEnd render_chunk(Renderer& renderer, const Claim& claim)
    {
        const ChunkRange range = m_job.plan.chunk(claim.n);
        const FrameControl& control = m_job.control;
        const bool limited = control.time_limit_seconds > 0.0;
        if (claim.pixels != m_selected) {
            if (claim.pixels) renderer.select_pixels(*claim.pixels);
            else renderer.select_all_pixels();
            m_selected = claim.pixels;
        }
        renderer.clear(range.first);
        ChunkEnd end;
        while (end.done < range.count) {
            if (m_shared.finished[claim.n].load() || m_shared.stop.load()) {
                end.abandoned = m_shared.finished[claim.n].load();
                end.stopped = !end.abandoned;
                break;
            }
            std::uint32_t wanted = range.count - end.done;
            if (limited)
                wanted = samples_before_deadline(control.time_limit_seconds - elapsed(), renderer.seconds_per_sample(),
                                                 wanted);
            end.done += renderer.render_samples(wanted);
            m_shared.progress[m_me] = end.done;
            report_progress(m_job, m_shared);
            // Rates from the second pass on: a first pass carries one-time costs (a driver's
            // first launch), which must not make a fast device look slow.
            if (++m_passes >= 2 && renderer.seconds_per_sample() > 0.0)
                m_shared.pass_rate[m_me] = 1.0 / renderer.seconds_per_sample();
            if (adds_too_little(m_shared.pass_rate[m_me].load(), m_shared.others_rate(m_me))) {
                m_report.left_slow = true;
                end.left = true;
                std::lock_guard lock(m_shared.mutex);
                leave_frame(m_shared, m_me, m_mine);
                return end;
            }
            const bool cancel = control.cancelled && control.cancelled();
            const bool late = limited && elapsed() >= control.time_limit_seconds && end.done < range.count;
            if (cancel || late) {
                std::lock_guard lock(m_shared.mutex);
                if (cancel) m_shared.cancelled = true;
                if (late && !cancel) m_shared.timed_out = true;
                m_shared.stop = true;
                m_shared.changed.notify_all();
                end.stopped = end.done < range.count;
                if (end.stopped) break;
            }
        }
        return end;
    }

    // Releases the chunk; delivers it to the sink if it is complete and first, or its samples
    // as a truncated chunk if the frame stopped part-way.
    void finish_chunk(Renderer& renderer, ChunkHandoff& handoff, const Claim& claim, const ChunkEnd& end)
    {
        const ChunkRange range = m_job.plan.chunk(claim.n);
        if (end.done > 0 && m_report.busy_seconds > 0)
            m_shared.seconds_per_sample[m_me] = m_report.busy_seconds / double(m_report.samples);
        m_shared.progress[m_me] = 0;
        bool deliver = false;
        bool truncated = false;
        {
            std::lock_guard lock(m_shared.mutex);
            m_shared.running[claim.n].erase(m_me);
            if (m_shared.running[claim.n].empty()) m_shared.running.erase(claim.n);
            m_mine.erase(std::find(m_mine.begin(), m_mine.end(), claim.n));
            if (!end.abandoned && end.done == range.count && !m_shared.finished[claim.n]) {
                m_shared.finished[claim.n] = true;
                ++m_shared.finished_count;
                deliver = true;
            } else if (end.stopped && end.done > 0 && !m_shared.finished[claim.n]) {
                truncated = true;
            }
            m_shared.changed.notify_all();
        }
        if (deliver) {
            ++m_report.chunks;
            if (claim.backup) ++m_report.backups;
            m_report.finished_at = seconds_between(m_start, Clock::now());
            m_shared.complete_samples += range.count;
            Shared& shared = m_shared;
            const FrameJob& job = m_job;
            handoff.hand_off(renderer, [&shared, &job, range](FilmSums&& sums) {
                std::lock_guard lock(shared.sink_mutex);
                job.sink(range, std::move(sums), true);
                shared.last_sunk = Clock::now();
                ++shared.sunk_count;
                if (job.rounds.active()) start_next_round_if_due(shared);
            });
        } else if (truncated) {
            ChunkRange cut = range;
            cut.count = end.done;
            FilmSums sums = renderer.sums(m_with_squares);
            std::lock_guard lock(m_shared.sink_mutex);
            m_job.sink(cut, std::move(sums), false);
            m_shared.last_sunk = Clock::now();
        }
    }

    const std::size_t m_me;
    const cl::DeviceInfo& m_device;
    const FrameJob& m_job;
    Shared& m_shared;
    DeviceReport& m_report;
    std::vector<std::uint32_t> m_mine;  // chunks this device holds in shared.running
    Clock::time_point m_start;          // the frame's start (every device set up)
    bool m_set_up = false;              // end_setup() was called
    bool m_with_squares = false;
    std::shared_ptr<const std::vector<std::uint32_t>> m_selected;  // the renderer's pick of pixels
    std::uint32_t m_passes = 0;
};

}  // namespace

FrameOutcome render_chunks(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                           const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                           const FrameControl& control, const ChunkSink& sink, const ChunkRounds& rounds)
{
    if (devices.empty()) throw UsageError("no device to render on");
    Shared shared(plan, devices.size(), rounds);
    shared.live = devices.size();
    shared.setting_up = devices.size();
    FrameOutcome outcome;
    outcome.devices.resize(devices.size());
    std::vector<std::exception_ptr> errors(devices.size());
    const auto called = Clock::now();
    const FrameJob job{prepared, settings, setup, plan, control, sink, rounds, called};

    std::vector<std::thread> threads;
    threads.reserve(devices.size());
    for (std::size_t i = 0; i < devices.size(); ++i)
        threads.emplace_back([&, i] { errors[i] = DeviceWorker(i, devices[i], job, shared, outcome.devices[i]).run(); });
    for (auto& t : threads) t.join();

    if (shared.round_error) std::rethrow_exception(shared.round_error);
    outcome.cancelled = shared.cancelled;
    outcome.timed_out = shared.timed_out;
    // The frame ends with its last chunk in the sink; the devices' clean-up after it (an
    // OpenCL context's release takes tens of milliseconds on NVIDIA's driver) is not rendering.
    const auto returned = Clock::now();
    const auto ended = shared.last_sunk ? *shared.last_sunk : returned;
    outcome.seconds = seconds_between(shared.start ? *shared.start : called, ended);
    outcome.seconds_with_setup = seconds_between(called, ended);
    outcome.cleanup_seconds = seconds_between(ended, returned);
    const bool stopped = shared.cancelled || shared.timed_out;
    if (!stopped && shared.finished_count < shared.queued_end()) {
        for (const auto& e : errors)
            if (e) std::rethrow_exception(e);
        throw DeviceError("the frame ended with chunks missing and no device error (a bug)");
    }
    for (std::size_t i = 0; i < devices.size(); ++i)
        if (!outcome.devices[i].failure.empty())
            log_warning("device " + outcome.devices[i].name + " dropped out of the frame: " + outcome.devices[i].failure);
    return outcome;
}

FrameResult render_frame(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                         const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                         const FrameControl& control, const FrameRounds& rounds)
{
    FrameAccumulator frame(plan);
    ChunkRounds chunk_rounds;
    if (rounds.pixels_after) {
        chunk_rounds.check_points = rounds.check_points;
        chunk_rounds.pixels_after = [&](std::uint32_t check_point) {
            return rounds.pixels_after(frame.frame(), check_point);
        };
    }
    FrameResult result;
    result.outcome = render_chunks(devices, prepared, settings, setup, plan, control,
                                   [&](const ChunkRange& range, FilmSums&& sums, bool complete) {
                                       if (complete) frame.add(range, std::move(sums));
                                       else frame.add_truncated(range, std::move(sums));
                                   },
                                   chunk_rounds);
    result.sums = frame.finish(&result.end_sample);
    return result;
}

}  // namespace gc
