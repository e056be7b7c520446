// Display transforms: each curve against values from its published definition, computed in
// double from the formulas as published (KhronosGroup/ToneMapping PBR_Neutral/README.md;
// Narkowicz 2016; AgX's sigmoid in bWFuanVzYWth/AgX's closed form and Wrensch's polynomial
// fit of Sobotka's LUT), and what write_image does with them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "host/image/display_transform.h"
#include "host/image/image_io.h"
#include "temp_dir.h"

namespace gc {
namespace {

void expect_rgb(const Rgb& got, const Rgb& want, float tolerance)
{
    for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tolerance) << "channel " << i;
}

TEST(DisplayTransform, PbrNeutralMatchesTheSpecification)
{
    // Below the compression start (p <= Ks = 0.76) the colour only loses the offset f:
    // f = 0.04 for min >= 0.08, x - x^2 / 0.16 below.
    expect_rgb(tonemap_pbr_neutral({0.5f, 0.5f, 0.5f}), {0.46f, 0.46f, 0.46f}, 1e-6f);
    expect_rgb(tonemap_pbr_neutral({0.8f, 0.2f, 0.1f}), {0.76f, 0.16f, 0.06f}, 1e-6f);
    expect_rgb(tonemap_pbr_neutral({0.02f, 0.02f, 0.02f}), {0.0025f, 0.0025f, 0.0025f}, 1e-7f);
    // Compressed: p_n = 1 - (1 - Ks)^2 / (p + 1 - 2 Ks), blended towards white by g.
    expect_rgb(tonemap_pbr_neutral({1.0f, 1.0f, 1.0f}), {0.8690909f, 0.8690909f, 0.8690909f}, 1e-6f);
    expect_rgb(tonemap_pbr_neutral({2.0f, 1.0f, 0.5f}), {0.96f, 0.5340905f, 0.3211358f}, 1e-6f);
    expect_rgb(tonemap_pbr_neutral({10.0f, 10.0f, 10.0f}), {0.9938983f, 0.9938983f, 0.9938983f}, 1e-6f);
    // Continuous where compression starts (p = Ks), and monotone above it.
    const Rgb below = tonemap_pbr_neutral({0.8f - 1e-4f, 0.8f - 1e-4f, 0.8f - 1e-4f});
    const Rgb above = tonemap_pbr_neutral({0.8f + 1e-4f, 0.8f + 1e-4f, 0.8f + 1e-4f});
    EXPECT_NEAR(below[0], above[0], 3e-4f);
    EXPECT_LT(below[0], above[0]);
}

TEST(DisplayTransform, AcesMatchesNarkowiczsFit)
{
    // x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clipped to [0, 1].
    expect_rgb(tonemap_aces({0.0f, 0.18f, 0.5f}), {0.0f, 0.2668989f, 0.6163070f}, 1e-6f);
    expect_rgb(tonemap_aces({1.0f, 4.0f, 16.0f}), {0.8037975f, 0.9734171f, 1.0f}, 1e-6f);
}

TEST(DisplayTransform, AgxSigmoidMatchesThePublishedCurves)
{
    // The closed form puts middle grey (log-encoded 20/33) at exactly 0.5 and spans [0, 1].
    EXPECT_NEAR(agx_sigmoid(20.0f / 33.0f), 0.5f, 1e-6f);
    EXPECT_NEAR(agx_sigmoid(0.0f), 0.0f, 1e-6f);
    EXPECT_NEAR(agx_sigmoid(1.0f), 1.0f, 1e-6f);
    // Wrensch's polynomial fit of Sobotka's LUT (mean squared error 3.7e-6) agrees within its
    // residual: 15.5x^6 - 40.14x^5 + 31.96x^4 - 6.868x^3 + 0.4298x^2 + 0.1191x - 0.00232.
    for (float x : {0.1f, 0.3f, 0.5f, 0.7f, 0.8f, 0.9f}) {
        const double d = x;
        const double fit = 15.5 * std::pow(d, 6) - 40.14 * std::pow(d, 5) + 31.96 * std::pow(d, 4) -
                           6.868 * d * d * d + 0.4298 * d * d + 0.1191 * d - 0.00232;
        EXPECT_NEAR(agx_sigmoid(x), fit, 5e-3) << "x = " << x;
    }
}

TEST(DisplayTransform, AgxMapsMiddleGreyToHalfTheDisplayRange)
{
    // 0.18 -> the sigmoid's 0.5 -> 0.5^2.2 display-linear (the inset rows sum to 1.00014,
    // so grey stays grey and moves by a hair).
    const Rgb grey = tonemap_agx({0.18f, 0.18f, 0.18f});
    for (float v : grey) EXPECT_NEAR(v, std::pow(0.5f, 2.2f), 2e-3f);
    // Very bright saturated colours desaturate towards white; black stays black.
    const Rgb red = tonemap_agx({1000.0f, 0.0f, 0.0f});
    EXPECT_GT(red[1], 0.5f);
    expect_rgb(tonemap_agx({0.0f, 0.0f, 0.0f}), {0.0f, 0.0f, 0.0f}, 1e-3f);
}

TEST(DisplayTransform, ExposureAndSanitizing)
{
    DisplayTransform clamp{Tonemap::Clamp, 1.0f};
    expect_rgb(apply_display_transform(clamp, {0.25f, 0.6f, -1.0f}), {0.5f, 1.0f, 0.0f}, 0.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (Tonemap t : {Tonemap::Clamp, Tonemap::PbrNeutral, Tonemap::Agx, Tonemap::Aces}) {
        const Rgb c = apply_display_transform({t, 0.0f}, {nan, std::numeric_limits<float>::infinity(), 0.3f});
        for (float v : c) {
            EXPECT_GE(v, 0.0f) << tonemap_name(t);
            EXPECT_LE(v, 1.0f) << tonemap_name(t);
        }
    }
    // pbr-neutral at +1 EV equals pbr-neutral of twice the value.
    const DisplayTransform neutral{Tonemap::PbrNeutral, 1.0f};
    expect_rgb(apply_display_transform(neutral, {0.5f, 0.5f, 0.5f}), tonemap_pbr_neutral({1.0f, 1.0f, 1.0f}), 1e-7f);
    EXPECT_TRUE(is_identity({Tonemap::None, 3.0f}));
    EXPECT_TRUE(is_identity({}));
    EXPECT_FALSE(is_identity(neutral));
}

class DisplayWrite : public test::TempDirTest {};

TEST_F(DisplayWrite, TransformsEightBitOutputsOnly)
{
    Film film(2, 1);
    film.set(0, 0, {1.0f, 1.0f, 1.0f, 1.0f});
    film.set(1, 0, {4.0f, 0.5f, 0.25f, 1.0f});
    write_image(path("a.pfm"), film, {}, {Tonemap::Agx, 2.0f});
    const Film linear = read_image(path("a.pfm"));
    EXPECT_EQ(linear.at(1, 0).r, 4.0f);  // float formats stay linear
    write_image(path("a.ppm"), film, {}, {Tonemap::PbrNeutral, 0.0f});
    const Film shown = read_image(path("a.ppm"));
    // 0.869 in the 8-bit sRGB encoding, not the clip's 255.
    EXPECT_NEAR(shown.at(0, 0).r, 0.8690909f, 0.01f);
    EXPECT_LT(shown.at(1, 0).r, 1.0f);
}

}  // namespace
}  // namespace gc
