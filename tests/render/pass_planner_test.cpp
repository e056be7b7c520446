// host/render/pass_planner: how the CPU path integrator sizes its passes from their times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "host/render/pass_planner.h"

namespace gc {
namespace {

// Runs passes of a render needing `spp` samples, each sample taking `per_sample` seconds;
// returns the samples of each pass.
std::vector<std::uint32_t> plan(PassPlanner& planner, std::uint32_t spp, double per_sample)
{
    std::vector<std::uint32_t> passes;
    std::string shown;
    for (std::uint32_t done = 0; done < spp;) {
        const std::uint32_t samples = planner.next(spp - done);
        planner.record(samples, samples * per_sample);
        passes.push_back(samples);
        done += samples;
        shown += " " + std::to_string(samples);
    }
    std::printf("%u spp at %.3f s per sample:%s\n", spp, per_sample, shown.c_str());
    return passes;
}

// 1, 2, 4 ... kMaxSamples: the passes of a plan that doubles up to the cap (together
// 2 kMaxSamples - 1 samples).
std::vector<std::uint32_t> doubling_to_the_cap()
{
    std::vector<std::uint32_t> passes;
    for (std::uint32_t n = 1; n <= PassPlanner::kMaxSamples; n *= 2) passes.push_back(n);
    return passes;
}

TEST(PassPlanner, QuickSamplesDoubleUpToTheCap)
{
    // 1 ms per sample: the half-second target holds 500, more than the cap.
    constexpr std::uint32_t cap = PassPlanner::kMaxSamples;
    static_assert(cap < 500);
    PassPlanner planner;
    EXPECT_FALSE(planner.settled());
    const std::vector<std::uint32_t> passes = plan(planner, 4 * cap, 0.001);
    std::vector<std::uint32_t> expected = doubling_to_the_cap();
    expected.insert(expected.end(), {cap, cap, 1u});
    EXPECT_EQ(passes, expected);
    EXPECT_TRUE(planner.settled());
}

TEST(PassPlanner, PassesStopGrowingAtTheTargetLength)
{
    // 0.1 s per sample: five fit into the half-second target.
    PassPlanner planner;
    const std::vector<std::uint32_t> passes = plan(planner, 20, 0.1);
    EXPECT_EQ(passes, (std::vector<std::uint32_t>{1, 2, 4, 5, 5, 3}));
    EXPECT_TRUE(planner.settled());
}

TEST(PassPlanner, SlowSamplesStayOnePerPass)
{
    PassPlanner planner;
    const std::vector<std::uint32_t> passes = plan(planner, 4, 2.0);
    EXPECT_EQ(passes, (std::vector<std::uint32_t>(4, 1u)));
    EXPECT_TRUE(planner.settled());
}

TEST(PassPlanner, ASlowFirstPassDoesNotSettleThePlan)
{
    // The first launch may include the driver's compile: one slow pass, then quick ones.
    PassPlanner planner;
    planner.record(planner.next(100), 3.0);
    EXPECT_EQ(planner.next(100), 1u);
    EXPECT_FALSE(planner.settled());
    const std::vector<std::uint32_t> passes = plan(planner, 2 * PassPlanner::kMaxSamples - 1, 0.001);
    EXPECT_EQ(passes, doubling_to_the_cap());
    EXPECT_TRUE(planner.settled());
}

TEST(PassPlanner, ASlowPassShrinksTheNext)
{
    PassPlanner planner;
    plan(planner, 31, 0.001);  // 1, 2, 4, 8, 16
    EXPECT_EQ(planner.next(100), 32u);
    planner.record(16, 16 * 0.2);  // the machine got busy: 0.2 s per sample
    EXPECT_EQ(planner.next(100), 2u);
}

TEST(PassPlanner, ALongRenderGrowsItsPassesToTwoSeconds)
{
    // 0.25 s per sample: two fill the first half-second passes; once a tenth of the time
    // rendered exceeds that, passes lengthen, up to 2 s (eight samples), never beyond.
    PassPlanner planner;
    const std::vector<std::uint32_t> passes = plan(planner, 200, 0.25);
    EXPECT_EQ(passes.front(), 1u);
    EXPECT_EQ(passes[1], 2u);
    EXPECT_EQ(*std::max_element(passes.begin(), passes.end()), 8u);
    EXPECT_EQ(passes[passes.size() - 2], 8u);
    double elapsed = 0.0;
    for (std::uint32_t p : passes) {
        EXPECT_LE(p * 0.25, std::max(PassPlanner::kMinTargetSeconds,
                                     std::min(PassPlanner::kMaxTargetSeconds, PassPlanner::kTargetShare * elapsed)) +
                                1e-9);
        elapsed += p * 0.25;
    }
    EXPECT_DOUBLE_EQ(planner.target_seconds(), PassPlanner::kMaxTargetSeconds);
    EXPECT_DOUBLE_EQ(planner.seconds_per_sample(), 0.25);
}

TEST(PassPlanner, ADeadlineCutsThePassToWhatFits)
{
    EXPECT_EQ(samples_before_deadline(1.0, 0.25, 16), 4u);
    EXPECT_EQ(samples_before_deadline(1.1, 0.25, 16), 5u);  // rounded up: the pass may cross it
    EXPECT_EQ(samples_before_deadline(10.0, 0.25, 16), 16u); // never more than remain
    EXPECT_EQ(samples_before_deadline(-3.0, 0.25, 16), 1u);  // past the deadline: one more
    EXPECT_EQ(samples_before_deadline(1.0, 0.0, 16), 16u);   // no time measured yet
}

TEST(PassPlanner, AFixedCountIsKeptAndNeverExceedsWhatIsLeft)
{
    PassPlanner planner(3);
    EXPECT_TRUE(planner.settled());
    EXPECT_EQ(planner.next(100), 3u);
    planner.record(3, 30.0);  // times do not matter
    EXPECT_EQ(planner.next(100), 3u);
    EXPECT_EQ(planner.next(2), 2u);
    EXPECT_EQ(plan(planner, 11, 0.001), (std::vector<std::uint32_t>{3, 3, 3, 2}));
}

TEST(PassPlanner, AZeroLengthPassDoesNotDivideByZero)
{
    PassPlanner planner;
    planner.record(1, 0.0);
    EXPECT_EQ(planner.next(100), 2u);
    EXPECT_EQ(planner.next(0), 1u);  // a caller asking for none still gets a valid count
}

}  // namespace
}  // namespace gc
