// gc_trig.h: the samplers' polynomial sine and cosine against double-precision std::sin/cos.
// The quarter-turn kernel is checked in ulps of the true value over a dense grid of
// [-pi/4, pi/4]; the turn-based form over [0, 1] in absolute error, because its argument
// 2 pi t is itself rounded (an angle's error, not a relative one, is what moves a direction).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gc_trig.h"

namespace gc::dev {
namespace {

constexpr double kPi = 3.14159265358979323846;

// |got - want| in units of the float spacing at want.
double ulps(float got, double want)
{
    const float w = static_cast<float>(want);
    const double spacing = std::nextafter(std::fabs(w), INFINITY) - std::fabs(w);
    return std::fabs(static_cast<double>(got) - want) / spacing;
}

TEST(Trig, QuarterTurnWithinAnUlpAndAHalf)
{
    constexpr int kSteps = 2000000;
    double worst_sin = 0.0;
    double worst_cos = 0.0;
    for (int i = -kSteps; i <= kSteps; ++i) {
        const float x = static_cast<float>(0.25 * kPi * i / kSteps);
        const float2 cs = gc_cos_sin_quarter(x);
        if (x != 0.0f) worst_sin = std::fmax(worst_sin, ulps(cs.y, std::sin(static_cast<double>(x))));
        worst_cos = std::fmax(worst_cos, ulps(cs.x, std::cos(static_cast<double>(x))));
    }
    std::printf("[trig] |x| <= pi/4, %d points: sin within %.3f ulp, cos within %.3f ulp (limits 1.0, 1.5)\n",
                2 * kSteps + 1, worst_sin, worst_cos);
    EXPECT_LE(worst_sin, 1.0);
    EXPECT_LE(worst_cos, 1.5);
    EXPECT_EQ(gc_cos_sin_quarter(0.0f).x, 1.0f);
    EXPECT_EQ(gc_cos_sin_quarter(0.0f).y, 0.0f);
}

TEST(Trig, TurnsMatchSinCosOfTwoPiT)
{
    // Every float t = k / 2^22 in [0, 1]: all quadrants and both sides of each quarter turn.
    constexpr int kSteps = 1 << 22;
    double worst = 0.0;
    double worst_norm = 0.0;
    for (int k = 0; k <= kSteps; ++k) {
        const float t = static_cast<float>(k) / static_cast<float>(kSteps);
        const float2 cs = gc_cos_sin_turns(t);
        const double phi = 2.0 * kPi * static_cast<double>(t);
        worst = std::fmax(worst, std::fmax(std::fabs(cs.x - std::cos(phi)), std::fabs(cs.y - std::sin(phi))));
        const double norm = static_cast<double>(cs.x) * cs.x + static_cast<double>(cs.y) * cs.y;
        worst_norm = std::fmax(worst_norm, std::fabs(norm - 1.0));
    }
    std::printf("[trig] t in [0, 1], %d points: |error| <= %.3g (limit 2.5e-7), |cos^2 + sin^2 - 1| <= %.3g (limit 4e-7)\n",
                kSteps + 1, worst, worst_norm);
    EXPECT_LE(worst, 2.5e-7);
    EXPECT_LE(worst_norm, 4e-7);
    // The quarter turns themselves are exact.
    EXPECT_EQ(gc_cos_sin_turns(0.0f), float2(1.0f, 0.0f));
    EXPECT_EQ(gc_cos_sin_turns(0.25f), float2(-0.0f, 1.0f));
    EXPECT_EQ(gc_cos_sin_turns(0.5f), float2(-1.0f, -0.0f));
    EXPECT_EQ(gc_cos_sin_turns(0.75f), float2(0.0f, -1.0f));
    EXPECT_EQ(gc_cos_sin_turns(1.0f), float2(1.0f, 0.0f));
}

// The environment map's lookup: angles of a dense grid of directions on the circle, in
// absolute error (the angle selects a texel).
TEST(Trig, ArcTangent)
{
    constexpr int kSteps = 1 << 21;
    double worst = 0.0;
    for (int k = 0; k < kSteps; ++k) {
        const double phi = 2.0 * kPi * (k + 0.5) / kSteps - kPi;
        const float x = static_cast<float>(std::cos(phi));
        const float y = static_cast<float>(std::sin(phi));
        const double want = std::atan2(static_cast<double>(y), static_cast<double>(x));
        worst = std::fmax(worst, std::fabs(gc_atan2(y, x) - want));
    }
    std::printf("[trig] atan2 on %d directions: |error| <= %.3g (limit 5e-7)\n", kSteps, worst);
    EXPECT_LE(worst, 5e-7);
    EXPECT_EQ(gc_atan2(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(gc_atan2(0.0f, 0.0f), 0.0f);
    EXPECT_FLOAT_EQ(gc_atan2(0.0f, -1.0f), static_cast<float>(kPi));
    EXPECT_FLOAT_EQ(gc_atan2(1.0f, 0.0f), static_cast<float>(kPi / 2));
    EXPECT_FLOAT_EQ(gc_atan2(-1.0f, 0.0f), static_cast<float>(-kPi / 2));
}

}  // namespace
}  // namespace gc::dev
