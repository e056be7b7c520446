// host/render/pass_planner: how the CPU path integrator sizes its passes from their times.
#include <gtest/gtest.h>

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

TEST(PassPlanner, QuickSamplesDoubleUpToTheCap)
{
    PassPlanner planner;
    EXPECT_FALSE(planner.settled());
    const std::vector<std::uint32_t> passes = plan(planner, 64, 0.001);
    EXPECT_EQ(passes, (std::vector<std::uint32_t>{1, 2, 4, 8, 16, 16, 16, 1}));
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
    const std::vector<std::uint32_t> passes = plan(planner, 31, 0.001);
    EXPECT_EQ(passes, (std::vector<std::uint32_t>{1, 2, 4, 8, 16}));
    EXPECT_TRUE(planner.settled());
}

TEST(PassPlanner, ASlowPassShrinksTheNext)
{
    PassPlanner planner;
    plan(planner, 31, 0.001);  // 1, 2, 4, 8, 16
    EXPECT_EQ(planner.next(100), 16u);
    planner.record(16, 16 * 0.2);  // the machine got busy: 0.2 s per sample
    EXPECT_EQ(planner.next(100), 2u);
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
