// The cdf searches of light sampling (gc_pick_emitter in gc_path.h, gc_env_search in
// gc_lights.h) against a linear scan: the first index whose cdf entry exceeds u, for every
// count from 1 to 70 and cdfs with repeated entries (zero-power emitters, black texels),
// with u drawn at random and placed exactly on entries and on both sides of them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "gc_lights.h"

namespace gc {
namespace {

// The first i in [0, n) with u < cdf[i + offset]; n - 1 when there is none.
std::uint32_t linear_scan(const std::vector<float>& cdf, std::uint32_t offset, std::uint32_t n, float u)
{
    for (std::uint32_t i = 0; i < n; ++i)
        if (u < cdf[i + offset]) return i;
    return n - 1;
}

// n + 1 entries 0 = c[0] <= c[1] <= ... <= c[n] = 1, about a third of the steps empty.
std::vector<float> random_cdf(std::uint32_t n, std::mt19937& rng)
{
    std::uniform_real_distribution<float> weight(0.0f, 1.0f);
    std::vector<float> w(n);
    for (float& x : w) x = (rng() % 3 == 0) ? 0.0f : weight(rng);
    w[rng() % n] += 0.5f;
    float total = 0.0f;
    for (float x : w) total += x;
    std::vector<float> cdf{0.0f};
    float sum = 0.0f;
    for (float x : w) cdf.push_back((sum += x) / total);
    cdf.back() = 1.0f;
    return cdf;
}

std::vector<float> probes(const std::vector<float>& cdf, std::mt19937& rng)
{
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::vector<float> u{0.0f, 0.99999994f};
    for (int k = 0; k < 64; ++k) u.push_back(uniform(rng));
    for (float c : cdf) {
        if (c >= 1.0f) continue;
        u.push_back(c);
        u.push_back(std::nextafter(c, 0.0f));
        u.push_back(std::nextafter(c, 1.0f));
    }
    return u;
}

TEST(LightSearch, PickEmitterEqualsLinearScan)
{
    std::mt19937 rng(3);
    std::size_t checked = 0;
    std::size_t differing = 0;
    for (std::uint32_t count = 1; count <= 70; ++count) {
        for (int trial = 0; trial < 8; ++trial) {
            const std::vector<float> cdf = random_cdf(count, rng);
            std::vector<dev::GcEmitter> emitters(count);
            for (std::uint32_t i = 0; i < count; ++i) emitters[i].cdf = cdf[i + 1];
            for (const float u : probes(cdf, rng)) {
                ++checked;
                differing += dev::gc_pick_emitter(emitters.data(), count, u) != linear_scan(cdf, 1, count, u);
            }
        }
    }
    std::printf("[search] emitters: %zu lookups, %zu differ from a linear scan\n", checked, differing);
    EXPECT_EQ(differing, 0u);
}

TEST(LightSearch, EnvironmentRowsAndColumnsEqualLinearScan)
{
    std::mt19937 rng(4);
    std::size_t checked = 0;
    std::size_t differing = 0;
    const dev::GcPointLight point_light{};
    const glm::vec4 pixel(0.0f);
    for (std::uint32_t n = 1; n <= 70; ++n) {
        for (int trial = 0; trial < 8; ++trial) {
            // Two rows of a conditional table: the search must add `base` for the second.
            std::vector<float> table = random_cdf(n, rng);
            const std::vector<float> second = random_cdf(n, rng);
            table.insert(table.end(), second.begin(), second.end());
            const std::uint32_t base = n + 1;
            for (const float u : probes(second, rng)) {
                ++checked;
                const std::uint32_t col = dev::gc_env_search(&point_light, &pixel, table.data(), table.data(), false, base, n, u);
                const std::uint32_t row = dev::gc_env_search(&point_light, &pixel, table.data(), table.data(), true, 0u, n, u);
                differing += col != linear_scan(table, base + 1, n, u);
                differing += row != linear_scan(table, 1, n, u);
            }
        }
    }
    std::printf("[search] environment: %zu lookups, %zu differ from a linear scan\n", checked, differing);
    EXPECT_EQ(differing, 0u);
}

}  // namespace
}  // namespace gc
