// clock_probe: how fast one core runs with every core busy, relative to one core alone, for
// scalar code and for 256- and 512-bit floating-point code. Each kernel is bound by the clock
// alone (dependent chains whose latency, or FMA ports kept full, set the pace; no memory), so
// its per-thread rate follows the core's frequency. A VM shows no clock; this shows its effect.
//
// Why: on the H200 host's Xeon our Cornell box path samples grew 12.4x from one thread to 16
// while Mitsuba 3's (16 AVX-512 lanes) grew 14.6x. If a core alone clocks higher for scalar
// code than for AVX-512 code, but all cores busy clock alike, a one-thread ratio flatters
// scalar code and a 16-thread ratio does not.
//
//   g++ -O2 -std=c++20 -pthread tools/bench/experiments/clock_probe.cpp -o clock_probe
//   ./clock_probe [seconds per run, default 2] [rounds, default 3] [threads, default every CPU]
//
// Prints, per kernel and round, the median per-thread rate with one thread and with all of
// them, and their ratio; then the median ratio per kernel.
//
// Two more modes (session 25), to tell apart what slows a thread when the others are busy:
//   ./clock_probe siblings [seconds, default 0.5]
//       CPU 0's rate alone and with one companion pinned to CPU k, for every k, running the
//       same kernel. A guest's "one thread per core" may still share a host core with
//       another vCPU (its SMT sibling): a port-bound kernel then loses up to half on that k.
//   ./clock_probe load KIND FIRST LAST SECONDS
//       Keeps CPUs FIRST..LAST busy with KIND (scalar, scalar-ipc, avx2-fma, avx512-fma) for
//       SECONDS, one pinned thread each, so that another program can be timed on the CPUs
//       left free while the rest of the package runs that kind of code.
#include <immintrin.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

// Each kernel runs `blocks` blocks of work and returns a value the caller keeps, so that the
// compiler cannot drop the work. One block is a fixed number of dependent steps.
constexpr int kStepsPerBlock = 4096;

// Scalar: one dependent chain of integer multiply-adds (latency-bound: about 4 cycles a step).
std::uint64_t scalar_blocks(std::uint64_t blocks, std::uint64_t seed)
{
    std::uint64_t x = seed | 1u;
    for (std::uint64_t b = 0; b < blocks; ++b)
        for (int i = 0; i < kStepsPerBlock; ++i) {
            x = x * 6364136223846793005ull + 1442695040888963407ull;
            asm volatile("" : "+r"(x));
        }
    return x;
}

// Scalar at high IPC: eight independent integer chains (add, shift, xor) that keep the ALU
// ports full, the kind of code an SMT sibling competes with.
std::uint64_t scalar_ipc_blocks(std::uint64_t blocks, std::uint64_t seed)
{
    std::uint64_t x0 = seed, x1 = seed + 1, x2 = seed + 2, x3 = seed + 3, x4 = seed + 4, x5 = seed + 5,
                  x6 = seed + 6, x7 = seed + 7;
    for (std::uint64_t b = 0; b < blocks; ++b)
        for (int i = 0; i < kStepsPerBlock / 8; ++i) {
            x0 = (x0 + 0x9e3779b97f4a7c15ull) ^ (x1 >> 7);
            x1 = (x1 + 0x632be59bd9b4e019ull) ^ (x2 << 9);
            x2 = (x2 + 0x85157af5ull) ^ (x3 >> 11);
            x3 = (x3 + 0x27bb2ee687b0b0fdull) ^ (x4 << 13);
            x4 = (x4 + 0x94d049bb133111ebull) ^ (x5 >> 5);
            x5 = (x5 + 0xbf58476d1ce4e5b9ull) ^ (x6 << 3);
            x6 = (x6 + 0x2545f4914f6cdd1dull) ^ (x7 >> 17);
            x7 = (x7 + 0x5851f42d4c957f2dull) ^ (x0 << 15);
            asm volatile("" : "+r"(x0), "+r"(x1), "+r"(x2), "+r"(x3), "+r"(x4), "+r"(x5), "+r"(x6), "+r"(x7));
        }
    return x0 ^ x1 ^ x2 ^ x3 ^ x4 ^ x5 ^ x6 ^ x7;
}

// Eight independent FMA chains in registers, enough to keep two FMA ports busy at 4 cycles of
// latency each; the empty asm keeps them in registers and each step's FMAs in place.
#define GC_EIGHT_FMA_CHAINS(VEC, SET1, FMA)                                                     \
    const VEC a = SET1(0.999999f);                                                              \
    const VEC c = SET1(1e-7f);                                                                  \
    VEC v0 = SET1(float(seed % 7)), v1 = v0, v2 = v0, v3 = v0, v4 = v0, v5 = v0, v6 = v0, v7 = v0; \
    for (std::uint64_t b = 0; b < blocks; ++b)                                                  \
        for (int i = 0; i < kStepsPerBlock / 8; ++i) {                                          \
            v0 = FMA(v0, a, c);                                                                 \
            v1 = FMA(v1, a, c);                                                                 \
            v2 = FMA(v2, a, c);                                                                 \
            v3 = FMA(v3, a, c);                                                                 \
            v4 = FMA(v4, a, c);                                                                 \
            v5 = FMA(v5, a, c);                                                                 \
            v6 = FMA(v6, a, c);                                                                 \
            v7 = FMA(v7, a, c);                                                                 \
            asm volatile("" : "+v"(v0), "+v"(v1), "+v"(v2), "+v"(v3), "+v"(v4), "+v"(v5), "+v"(v6), "+v"(v7)); \
        }

// 256-bit (AVX2 + FMA).
__attribute__((target("avx2,fma"))) std::uint64_t avx2_blocks(std::uint64_t blocks, std::uint64_t seed)
{
    GC_EIGHT_FMA_CHAINS(__m256, _mm256_set1_ps, _mm256_fmadd_ps)
    const __m256 s = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(v0, v1), _mm256_add_ps(v2, v3)),
                                   _mm256_add_ps(_mm256_add_ps(v4, v5), _mm256_add_ps(v6, v7)));
    return std::uint64_t(_mm256_cvtss_f32(s));
}

// 512-bit (AVX-512F): the same in zmm registers.
__attribute__((target("avx512f"))) std::uint64_t avx512_blocks(std::uint64_t blocks, std::uint64_t seed)
{
    GC_EIGHT_FMA_CHAINS(__m512, _mm512_set1_ps, _mm512_fmadd_ps)
    const __m512 s = _mm512_add_ps(_mm512_add_ps(_mm512_add_ps(v0, v1), _mm512_add_ps(v2, v3)),
                                   _mm512_add_ps(_mm512_add_ps(v4, v5), _mm512_add_ps(v6, v7)));
    alignas(64) float lanes[16];
    _mm512_store_ps(lanes, s);
    return std::uint64_t(lanes[0] + lanes[15]);
}

struct Kernel {
    const char* name;
    std::uint64_t (*run)(std::uint64_t, std::uint64_t);
};

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::atomic<std::uint64_t> g_sink{0};

// Runs `kernel` on the calling thread for about `seconds`; returns its blocks per second.
double blocks_per_second(const Kernel& kernel, std::uint64_t seed, double seconds)
{
    const auto start = Clock::now();
    std::uint64_t blocks = 0, sink = 0;
    double elapsed = 0.0;
    while (elapsed < seconds) {
        sink += kernel.run(64, blocks + seed);
        blocks += 64;
        elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    }
    g_sink.fetch_add(sink);
    return double(blocks) / elapsed;
}

// Runs `kernel` on `threads` threads for about `seconds`; returns the median per-thread rate
// in blocks per second. The threads start together and each times only its own work.
double per_thread_rate(const Kernel& kernel, int threads, double seconds)
{
    std::vector<double> rates(static_cast<std::size_t>(threads));
    std::atomic<int> ready{0};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            ready.fetch_add(1);
            while (ready.load() < threads) {
            }
            rates[static_cast<std::size_t>(t)] = blocks_per_second(kernel, static_cast<std::uint64_t>(t), seconds);
        });
    for (std::thread& th : pool) th.join();
    return median(rates);
}

// Pins the calling thread to one CPU; false where the CPU is not ours to run on.
bool pin_to_cpu(int cpu)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    return pthread_setaffinity_np(pthread_self(), sizeof(set), &set) == 0;
}

const Kernel* kernel_named(const std::vector<Kernel>& kernels, const std::string& name)
{
    for (const Kernel& k : kernels)
        if (name == k.name) return &k;
    return nullptr;
}

// Runs `kernel` on the calling thread for as long as `keep_going()` says, counting nothing:
// the load that companions and `load` mode put on other CPUs.
template <class KeepGoing>
void run_while(const Kernel& kernel, KeepGoing keep_going)
{
    std::uint64_t sink = 0, blocks = 0;
    while (keep_going()) sink += kernel.run(64, blocks += 64);
    g_sink.fetch_add(sink);
}

// Blocks per second of `kernel` on CPU 0 for `seconds`, while `companion_cpu` (if >= 0) runs
// the same kernel for as long.
double rate_on_cpu0(const Kernel& kernel, int companion_cpu, double seconds)
{
    std::atomic<bool> stop{false};
    std::thread companion;
    if (companion_cpu >= 0)
        companion = std::thread([&] {
            pin_to_cpu(companion_cpu);
            run_while(kernel, [&] { return !stop.load(); });
        });
    double rate = 0.0;
    std::thread measured([&] {
        pin_to_cpu(0);
        rate = blocks_per_second(kernel, 0, seconds);
    });
    measured.join();
    stop = true;
    if (companion.joinable()) companion.join();
    return rate;
}

int siblings_mode(const std::vector<Kernel>& kernels, double seconds)
{
    const int cpus = static_cast<int>(std::thread::hardware_concurrency());
    std::printf("clock_probe siblings: CPU 0's rate with a companion on CPU k over CPU 0 alone (alone measured "
                "before and after each k), %.2f s per run\n", seconds);
    for (const Kernel& k : kernels) {
        std::printf("  %-10s", k.name);
        for (int cpu = 1; cpu < cpus; ++cpu) {
            const double before = rate_on_cpu0(k, -1, seconds);
            const double paired = rate_on_cpu0(k, cpu, seconds);
            const double after = rate_on_cpu0(k, -1, seconds);
            std::printf(" %d:%.2f", cpu, paired / (0.5 * (before + after)));
            std::fflush(stdout);
        }
        std::printf("\n");
    }
    return 0;
}

int load_mode(const std::vector<Kernel>& kernels, const std::string& kind, int first, int last, double seconds)
{
    const Kernel* kernel = kernel_named(kernels, kind);
    if (!kernel || first < 0 || last < first || !(seconds > 0.0)) {
        std::fprintf(stderr, "usage: clock_probe load scalar|scalar-ipc|avx2-fma|avx512-fma FIRST LAST SECONDS\n");
        return 2;
    }
    std::vector<std::thread> pool;
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    for (int cpu = first; cpu <= last; ++cpu)
        pool.emplace_back([&, cpu] {
            if (!pin_to_cpu(cpu)) std::fprintf(stderr, "clock_probe: cannot pin to CPU %d\n", cpu);
            run_while(*kernel, [&] { return Clock::now() < end; });
        });
    for (std::thread& th : pool) th.join();
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<Kernel> kernels = {{"scalar", scalar_blocks}, {"scalar-ipc", scalar_ipc_blocks}, {"avx2-fma", avx2_blocks}};
    if (__builtin_cpu_supports("avx512f")) kernels.push_back({"avx512-fma", avx512_blocks});
    if (argc > 1 && std::strcmp(argv[1], "siblings") == 0)
        return siblings_mode(kernels, argc > 2 ? std::atof(argv[2]) : 0.5);
    if (argc > 1 && std::strcmp(argv[1], "load") == 0) {
        if (argc != 6) return load_mode(kernels, "", -1, -1, 0.0);
        return load_mode(kernels, argv[2], std::atoi(argv[3]), std::atoi(argv[4]), std::atof(argv[5]));
    }
    const double seconds = argc > 1 ? std::atof(argv[1]) : 2.0;
    const int rounds = argc > 2 ? std::atoi(argv[2]) : 3;
    const int threads = argc > 3 ? std::atoi(argv[3]) : static_cast<int>(std::thread::hardware_concurrency());
    if (!(seconds > 0.0) || rounds < 1 || threads < 1) {
        std::fprintf(stderr, "usage: clock_probe [seconds > 0] [rounds >= 1] [threads >= 1]\n");
        return 2;
    }
    std::printf("clock_probe: %d threads, %.1f s per run, %d rounds; per-thread rate with all threads busy / "
                "with one thread\n", threads, seconds, rounds);
    for (const Kernel& k : kernels) {
        std::vector<double> ratios;
        for (int r = 0; r < rounds; ++r) {
            const double one = per_thread_rate(k, 1, seconds);
            const double all = per_thread_rate(k, threads, seconds);
            ratios.push_back(all / one);
            std::printf("  %-10s round %d: one thread %.4g blocks/s, %d threads %.4g per thread = %.3fx", k.name, r + 1,
                        one, threads, all, all / one);
            // A scalar step is a 64-bit multiply (3 cycles) and an add (1) on current x86 cores.
            if (k.run == scalar_blocks)
                std::printf(" (about %.2f and %.2f GHz at 4 cycles a step)", one * kStepsPerBlock * 4 / 1e9,
                            all * kStepsPerBlock * 4 / 1e9);
            std::printf("\n");
        }
        std::printf("%-10s median %.3fx\n", k.name, median(ratios));
    }
    return g_sink.load() == 42 ? 1 : 0;  // never 42 in practice: keeps the work observable
}
