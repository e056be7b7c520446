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
    std::exception_ptr round_error;  // a pick that threw: the frame stops and render_chunks rethrows it
    std::vector<std::atomic<std::uint32_t>> progress;     // samples of its current chunk, per device
    std::vector<std::atomic<double>> chunk_started;       // when it started its current chunk (frame seconds)
    std::vector<std::atomic<double>> seconds_per_sample;  // per device, 0 = not known yet
    std::vector<std::atomic<double>> pass_rate;  // samples per second of its last pass; 0: unknown or gone
    std::atomic<bool> stop{false};
    bool cancelled = false;
    bool timed_out = false;
    std::size_t live = 0;
    std::optional<Clock::time_point> start;  // the first device ready
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

FrameOutcome render_chunks(const std::vector<cl::DeviceInfo>& devices, const PreparedScene& prepared,
                           const RenderSettings& settings, const RenderSetup& setup, const ChunkPlan& plan,
                           const FrameControl& control, const ChunkSink& sink, const ChunkRounds& rounds)
{
    if (devices.empty()) throw UsageError("no device to render on");
    Shared shared(plan, devices.size(), rounds);
    shared.live = devices.size();
    FrameOutcome outcome;
    outcome.devices.resize(devices.size());
    std::vector<std::exception_ptr> errors(devices.size());
    const auto called = Clock::now();

    const auto report_progress = [&] {
        if (!control.on_progress) return;
        std::uint64_t done = shared.complete_samples.load();
        for (const auto& p : shared.progress) done += p.load();
        std::lock_guard lock(shared.progress_mutex);
        control.on_progress(std::min<std::uint64_t>(done, plan.end_sample - plan.first_sample));
    };

    const auto worker = [&](std::size_t me) {
        const cl::DeviceInfo& device = devices[me];
        DeviceReport& report = outcome.devices[me];
        report.name = device.device_name + " (" + device.platform_name + ")";
        report.is_gpu = device.is_gpu;
        std::vector<std::uint32_t> mine;  // chunks this device holds in `running`
        try {
            const auto setup_start = Clock::now();
            Session session(device, prepared, settings, setup);
            Renderer& renderer = session.renderer();
            const bool with_squares = control.with_squares || rounds.active();
            ChunkHandoff handoff(session.context(), renderer, with_squares);
            report.setup_seconds = seconds_between(setup_start, Clock::now());
            Clock::time_point start;
            {
                std::lock_guard lock(shared.mutex);
                if (!shared.start) shared.start = Clock::now();
                start = *shared.start;
            }
            const auto elapsed = [&] { return seconds_between(start, Clock::now()); };
            const bool limited = control.time_limit_seconds > 0.0;
            std::shared_ptr<const std::vector<std::uint32_t>> selected;  // the renderer's pick
            std::uint32_t passes = 0;

            // Returns when the plan is done or the frame stops.
            const auto render_chunks_until_done = [&] {
                for (;;) {
                    std::uint32_t n = 0;
                    bool backup = false;
                    std::shared_ptr<const std::vector<std::uint32_t>> pixels;
                    {
                        std::unique_lock lock(shared.mutex);
                        for (;;) {
                            if (shared.stop) return;
                            auto& own = shared.reserved[me];
                            if (own.empty() && !shared.todo.empty()) {
                                const std::uint32_t want = ask_size(device.is_gpu, std::uint32_t(shared.todo.size()),
                                                                    std::uint32_t(shared.live));
                                for (std::uint32_t i = 0; i < want && !shared.todo.empty(); ++i) {
                                    own.push_back(shared.todo.front());
                                    shared.todo.pop_front();
                                }
                            }
                            if (own.empty()) {
                                // Take a chunk another device reserved and has not started.
                                for (auto& other : shared.reserved)
                                    if (other.size() > 0 && &other != &own) {
                                        own.push_back(other.back());
                                        other.pop_back();
                                        break;
                                    }
                            }
                            if (!own.empty()) {
                                n = own.front();
                                own.pop_front();
                                break;
                            }
                            // Nothing left to take: back up the running chunk that its holder
                            // will finish last, if this device expects to finish it sooner.
                            const double mine_spp = shared.seconds_per_sample[me].load();
                            double best_gain = 0.0;
                            std::optional<std::uint32_t> pick;
                            for (const auto& [chunk, holders] : shared.running) {
                                if (holders.size() != 1 || holders.count(me)) continue;
                                const std::size_t holder = *holders.begin();
                                RunningChunk running;
                                running.count = plan.chunk(chunk).count;
                                running.done = shared.progress[holder].load();
                                running.elapsed_seconds = elapsed() - shared.chunk_started[holder].load();
                                running.holder_seconds_per_sample = shared.seconds_per_sample[holder].load();
                                const double gain = backup_gain(mine_spp, running);
                                if (gain > best_gain) {
                                    best_gain = gain;
                                    pick = chunk;
                                }
                            }
                            if (pick) {
                                n = *pick;
                                backup = true;
                                break;
                            }
                            if (shared.running.empty() && shared.todo.empty() && !shared.round_pending()) {
                                bool any_reserved = false;
                                for (const auto& r : shared.reserved) any_reserved = any_reserved || !r.empty();
                                if (!any_reserved) return;  // the plan is done
                            }
                            shared.changed.wait_for(lock, std::chrono::milliseconds(20));
                        }
                        shared.running[n].insert(me);
                        mine.push_back(n);
                        pixels = shared.pixels;
                    }

                    const ChunkRange range = plan.chunk(n);
                    const auto chunk_start = Clock::now();
                    shared.chunk_started[me] = seconds_between(start, chunk_start);
                    if (pixels != selected) {
                        if (pixels) renderer.select_pixels(*pixels);
                        else renderer.select_all_pixels();
                        selected = pixels;
                    }
                    renderer.clear(range.first);
                    std::uint32_t done = 0;
                    bool abandoned = false;
                    bool stopped = false;
                    while (done < range.count) {
                        if (shared.finished[n].load() || shared.stop.load()) {
                            abandoned = shared.finished[n].load();
                            stopped = !abandoned;
                            break;
                        }
                        std::uint32_t wanted = range.count - done;
                        if (limited)
                            wanted = samples_before_deadline(control.time_limit_seconds - elapsed(),
                                                             renderer.seconds_per_sample(), wanted);
                        done += renderer.render_samples(wanted);
                        shared.progress[me] = done;
                        report_progress();
                        // Rates from the second pass on: a first pass carries one-time costs (a
                        // driver's first launch), which must not make a fast device look slow.
                        if (++passes >= 2 && renderer.seconds_per_sample() > 0.0)
                            shared.pass_rate[me] = 1.0 / renderer.seconds_per_sample();
                        if (adds_too_little(shared.pass_rate[me].load(), shared.others_rate(me))) {
                            report.busy_seconds += seconds_between(chunk_start, Clock::now());
                            report.samples += done;
                            report.left_slow = true;
                            std::lock_guard lock(shared.mutex);
                            leave_frame(shared, me, mine);
                            return;
                        }
                        const bool cancel = control.cancelled && control.cancelled();
                        const bool late = limited && elapsed() >= control.time_limit_seconds && done < range.count;
                        if (cancel || late) {
                            std::lock_guard lock(shared.mutex);
                            if (cancel) shared.cancelled = true;
                            if (late && !cancel) shared.timed_out = true;
                            shared.stop = true;
                            shared.changed.notify_all();
                            stopped = done < range.count;
                            if (stopped) break;
                        }
                    }
                    const double chunk_seconds = seconds_between(chunk_start, Clock::now());
                    report.busy_seconds += chunk_seconds;
                    report.samples += done;
                    if (done > 0 && report.busy_seconds > 0)
                        shared.seconds_per_sample[me] = report.busy_seconds / double(report.samples);
                    shared.progress[me] = 0;

                    bool deliver = false;
                    bool truncated = false;
                    {
                        std::lock_guard lock(shared.mutex);
                        shared.running[n].erase(me);
                        if (shared.running[n].empty()) shared.running.erase(n);
                        mine.erase(std::find(mine.begin(), mine.end(), n));
                        if (!abandoned && done == range.count && !shared.finished[n]) {
                            shared.finished[n] = true;
                            ++shared.finished_count;
                            deliver = true;
                        } else if (stopped && done > 0 && !shared.finished[n]) {
                            truncated = true;
                        }
                        shared.changed.notify_all();
                    }
                    if (deliver) {
                        ++report.chunks;
                        if (backup) ++report.backups;
                        report.finished_at = seconds_between(start, Clock::now());
                        shared.complete_samples += range.count;
                        handoff.hand_off(renderer, [&shared, &sink, &rounds, range](FilmSums&& sums) {
                            std::lock_guard lock(shared.sink_mutex);
                            sink(range, std::move(sums), true);
                            ++shared.sunk_count;
                            if (rounds.active()) start_next_round_if_due(shared);
                        });
                    } else if (truncated) {
                        ChunkRange cut = range;
                        cut.count = done;
                        FilmSums sums = renderer.sums(with_squares);
                        std::lock_guard lock(shared.sink_mutex);
                        sink(cut, std::move(sums), false);
                    }
                    if (stopped) return;
                }
            };
            render_chunks_until_done();
            handoff.wait();
        } catch (...) {
            errors[me] = std::current_exception();
            try {
                std::rethrow_exception(errors[me]);
            } catch (const std::exception& e) {
                report.failure = e.what();
            } catch (...) {
                report.failure = "unknown error";
            }
            std::lock_guard lock(shared.mutex);
            leave_frame(shared, me, mine);
        }
    };

    std::vector<std::thread> threads;
    threads.reserve(devices.size());
    for (std::size_t i = 0; i < devices.size(); ++i) threads.emplace_back(worker, i);
    for (auto& t : threads) t.join();

    if (shared.round_error) std::rethrow_exception(shared.round_error);
    outcome.cancelled = shared.cancelled;
    outcome.timed_out = shared.timed_out;
    outcome.seconds = shared.start ? seconds_between(*shared.start, Clock::now()) : seconds_between(called, Clock::now());
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
