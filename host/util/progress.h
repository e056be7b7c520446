// A one-line progress bar on stderr for long renders:
//   render  [#########...........]  45%  00:12 elapsed  ETA 00:15  3.21 Mspp/s
// Redrawn in place (carriage return) at most ~10 times a second so printing never costs
// render time. Silent with `quiet` or when stderr is not a terminal (logs and CI stay clean).
// update() and finish() lock a mutex: one render thread reporting while another (a signal
// watcher, say) finishes is fine.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace gc {

class ProgressBar {
public:
    struct Options {
        bool quiet = false;
        std::FILE* out = nullptr;     // nullptr: stderr
        bool force = false;           // draw even when `out` is not a TTY (tests)
        std::string unit = "units";  // throughput unit, e.g. "spp" or "rays"
        int min_interval_ms = 100;    // redraw rate limit
    };

    ProgressBar(std::string label, uint64_t total);
    ProgressBar(std::string label, uint64_t total, Options options);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    // `done` units of `total` are complete. Redraws if the last draw is old enough.
    void update(uint64_t done);
    // Draws the final state (done = total unless update() said otherwise) and a newline. Idempotent.
    void finish();

    bool enabled() const { return m_enabled; }

    // The line as drawn, without the leading '\r': for tests and for logs.
    static std::string format_line(const std::string& label, uint64_t done, uint64_t total, double elapsed_s,
                                   const std::string& unit, int bar_width = 24);
    // "1.50 k", "3.21 M"... with SI prefixes.
    static std::string format_rate(double per_second, const std::string& unit);
    // "mm:ss", or "h:mm:ss" past an hour; "--:--" for unknown (negative / non-finite).
    static std::string format_duration(double seconds);

private:
    void draw_locked(bool final_line);

    std::string m_label;
    uint64_t m_total;
    Options m_options;
    bool m_enabled;
    bool m_finished = false;
    bool m_drawn = false;
    uint64_t m_done = 0;
    std::chrono::steady_clock::time_point m_start;
    std::chrono::steady_clock::time_point m_last_draw;
    std::mutex m_mutex;
};

}  // namespace gc
