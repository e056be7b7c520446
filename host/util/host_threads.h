// How many threads the host's parallel work may use (the BVH build, its collapse into the
// wide CPU layouts, the triangle layout): every core unless the command line said otherwise
// (geocold-cl --threads). Header-only so that every host library can ask.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>

namespace gc {

inline std::atomic<int>& host_thread_limit_storage()
{
    static std::atomic<int> limit{0};  // 0: every core
    return limit;
}

// Set once, at start-up, before any parallel work. 0 restores "every core".
inline void set_host_thread_count(int threads) { host_thread_limit_storage() = std::max(0, threads); }

// At least 1.
inline int host_thread_count()
{
    const int limit = host_thread_limit_storage().load();
    return limit > 0 ? limit : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace gc
