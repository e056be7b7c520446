#include "host/util/progress.h"

#include <algorithm>
#include <cmath>

#include <unistd.h>

namespace gc {

ProgressBar::ProgressBar(std::string label, uint64_t total) : ProgressBar(std::move(label), total, Options{}) {}

ProgressBar::ProgressBar(std::string label, uint64_t total, Options options)
    : m_label(std::move(label)), m_total(total), m_options(std::move(options)), m_start(std::chrono::steady_clock::now())
{
    if (!m_options.out) m_options.out = stderr;
    m_enabled = !m_options.quiet && (m_options.force || ::isatty(::fileno(m_options.out)) == 1);
    m_last_draw = m_start;
}

ProgressBar::~ProgressBar()
{
    // Unwinding past an unfinished bar (an exception mid-render): end the line so the error
    // message starts on its own line, but don't pretend the work completed.
    std::lock_guard lock(m_mutex);
    if (m_enabled && m_drawn && !m_finished) std::fputc('\n', m_options.out);
}

void ProgressBar::update(uint64_t done)
{
    if (!m_enabled) return;
    std::lock_guard lock(m_mutex);
    if (m_finished) return;
    m_done = std::min(done, m_total);
    const auto now = std::chrono::steady_clock::now();
    if (m_drawn && now - m_last_draw < std::chrono::milliseconds(m_options.min_interval_ms)) return;
    m_last_draw = now;
    draw_locked(false);
}

void ProgressBar::finish()
{
    if (!m_enabled) return;
    std::lock_guard lock(m_mutex);
    if (m_finished) return;
    m_finished = true;
    if (!m_drawn) m_done = m_total;  // finish() without updates: the work was all done
    draw_locked(true);
}

void ProgressBar::draw_locked(bool final_line)
{
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    const std::string line = format_line(m_label, m_done, m_total, elapsed, m_options.unit);
    // Trailing spaces wipe what a longer previous line left behind.
    std::fprintf(m_options.out, "\r%s   %s", line.c_str(), final_line ? "\n" : "");
    std::fflush(m_options.out);
    m_drawn = true;
}

std::string ProgressBar::format_duration(double seconds)
{
    if (!std::isfinite(seconds) || seconds < 0) return "--:--";
    const auto s = uint64_t(seconds + 0.5);
    char buf[32];
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%llu:%02llu:%02llu", (unsigned long long)(s / 3600),
                      (unsigned long long)(s / 60 % 60), (unsigned long long)(s % 60));
    else
        std::snprintf(buf, sizeof buf, "%02llu:%02llu", (unsigned long long)(s / 60), (unsigned long long)(s % 60));
    return buf;
}

std::string ProgressBar::format_rate(double per_second, const std::string& unit)
{
    static const char* const prefixes[] = {"", "k", "M", "G", "T"};
    int i = 0;
    double v = std::isfinite(per_second) ? std::max(per_second, 0.0) : 0.0;
    while (v >= 1000.0 && i < 4) {
        v /= 1000.0;
        ++i;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f %s%s/s", v < 10 ? 2 : (v < 100 ? 1 : 0), v, prefixes[i], unit.c_str());
    return buf;
}

std::string ProgressBar::format_line(const std::string& label, uint64_t done, uint64_t total, double elapsed_s,
                                     const std::string& unit, int bar_width)
{
    const double fraction = total > 0 ? std::min(1.0, double(done) / double(total)) : 1.0;
    const int filled = int(fraction * bar_width);
    std::string bar(size_t(filled), '#');
    bar.append(size_t(bar_width - filled), '.');
    // ETA from the average rate so far; unknown until something is done.
    const double eta = done > 0 ? elapsed_s * (double(total) - double(done)) / double(done) : -1.0;
    const double rate = elapsed_s > 0 ? double(done) / elapsed_s : 0.0;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%3d%%", int(fraction * 100.0));
    return label + "  [" + bar + "] " + buf + "  " + format_duration(elapsed_s) + " elapsed  ETA " +
           format_duration(eta) + "  " + format_rate(rate, unit);
}

}  // namespace gc
