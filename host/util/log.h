// Diagnostics on stderr, prefixed with the program name. Warnings are for things the user
// should know but that do not stop the render (a missing .mtl, a clamped material).
#pragma once

#include <atomic>
#include <cstdio>
#include <string>

namespace gc {

enum class LogLevel : int { Quiet = 0, Normal = 1, Verbose = 2 };

inline std::atomic<int>& log_level_storage()
{
    static std::atomic<int> level{static_cast<int>(LogLevel::Normal)};
    return level;
}
inline void set_log_level(LogLevel level) { log_level_storage() = static_cast<int>(level); }
inline LogLevel log_level() { return static_cast<LogLevel>(log_level_storage().load()); }

// Warnings are printed even with --quiet: quiet silences progress, not problems.
inline void log_warning(const std::string& message)
{
    std::fprintf(stderr, "geocold-cl: warning: %s\n", message.c_str());
}
inline void log_info(const std::string& message)
{
    if (log_level() >= LogLevel::Normal) std::fprintf(stderr, "geocold-cl: %s\n", message.c_str());
}
inline void log_verbose(const std::string& message)
{
    if (log_level() >= LogLevel::Verbose) std::fprintf(stderr, "geocold-cl: %s\n", message.c_str());
}

}  // namespace gc
