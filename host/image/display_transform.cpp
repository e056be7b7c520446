#include "host/image/display_transform.h"

#include <algorithm>
#include <cmath>

namespace gc {
namespace {

float sanitize(float v) { return v > 0.0f ? v : 0.0f; }  // NaN fails the comparison too

float clamp01(float v) { return v > 0.0f ? std::fmin(v, 1.0f) : 0.0f; }

// out = m * c with m given row by row.
Rgb multiply(const double (&m)[3][3], const Rgb& c)
{
    Rgb out{};
    for (int i = 0; i < 3; ++i)
        out[size_t(i)] = float(m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2]);
    return out;
}

// AgX's inset and outset matrices, as rows (the GLSL sources list them column by column).
constexpr double k_agx_inset[3][3] = {
    {0.842479062253094, 0.0784335999999992, 0.0792237451477643},
    {0.0423282422610123, 0.878468636469772, 0.0791661274605434},
    {0.0423756549057051, 0.0784336, 0.879142973793104},
};
constexpr double k_agx_outset[3][3] = {
    {1.19687900512017, -0.0980208811401368, -0.0990297440797205},
    {-0.0528968517574562, 1.15190312990417, -0.0989611768448433},
    {-0.0529716355144438, -0.0980434501171241, 1.15107367264116},
};
// log2(0.18) - 10 and log2(0.18) + 6.5: 16.5 stops around middle grey.
constexpr double k_agx_min_ev = -12.47393;
constexpr double k_agx_max_ev = 4.026069;

}  // namespace

std::optional<Tonemap> parse_tonemap(std::string_view name)
{
    if (name == "none") return Tonemap::None;
    if (name == "clamp") return Tonemap::Clamp;
    if (name == "pbr-neutral") return Tonemap::PbrNeutral;
    if (name == "agx") return Tonemap::Agx;
    if (name == "aces") return Tonemap::Aces;
    return std::nullopt;
}

const char* tonemap_name(Tonemap tonemap)
{
    switch (tonemap) {
    case Tonemap::None: return "none";
    case Tonemap::Clamp: return "clamp";
    case Tonemap::PbrNeutral: return "pbr-neutral";
    case Tonemap::Agx: return "agx";
    case Tonemap::Aces: return "aces";
    }
    return "?";
}

const char* tonemap_names() { return "none|clamp|pbr-neutral|agx|aces"; }

Rgb tonemap_pbr_neutral(Rgb c)
{
    // The specification's symbols: F90 = 0.04, Ks = 0.8 - F90, Kd = 0.15.
    constexpr float f90 = 0.04f, ks = 0.8f - f90, kd = 0.15f;
    const float x = std::min({c[0], c[1], c[2]});
    const float f = x <= 2.0f * f90 ? x - x * x / (4.0f * f90) : f90;
    for (float& v : c) v -= f;
    const float p = std::max({c[0], c[1], c[2]});
    if (p <= ks) return c;
    const float pn = 1.0f - (1.0f - ks) * (1.0f - ks) / (p + 1.0f - 2.0f * ks);
    const float g = 1.0f / (kd * (p - pn) + 1.0f);
    for (float& v : c) v = v * (pn / p) * g + pn * (1.0f - g);
    return c;
}

float agx_sigmoid(float x)
{
    // Sobotka's default sigmoid in closed form: two power curves meeting at 20/33 (middle
    // grey's position in the log encoding), where the value is 0.5.
    const double t = 20.0 / 33.0;
    const double v = x;
    const bool low = v <= t;
    const double a = low ? 59.507875 : 69.86278913545539;
    const double b = low ? 3.0 : 13.0 / 4.0;
    const double e = low ? -1.0 / 3.0 : -4.0 / 13.0;
    return float(0.5 + (2.0 * v - 2.0 * t) * std::pow(1.0 + a * std::pow(std::fabs(v - t), b), e));
}

Rgb tonemap_agx(Rgb c)
{
    Rgb v = multiply(k_agx_inset, c);
    for (float& x : v) {
        const double ev = x > 0.0f ? std::clamp(std::log2(double(x)), k_agx_min_ev, k_agx_max_ev) : k_agx_min_ev;
        x = agx_sigmoid(float((ev - k_agx_min_ev) / (k_agx_max_ev - k_agx_min_ev)));
    }
    v = multiply(k_agx_outset, v);
    for (float& x : v) x = clamp01(std::pow(clamp01(x), 2.2f));  // the display's 2.2 EOTF
    return v;
}

Rgb tonemap_aces(Rgb c)
{
    for (float& x : c) x = clamp01(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f));
    return c;
}

Rgb apply_display_transform(const DisplayTransform& display, Rgb linear)
{
    if (display.tonemap == Tonemap::None) return linear;
    const float scale = std::exp2(display.exposure_ev);
    for (float& v : linear) v = sanitize(v) * scale;
    switch (display.tonemap) {
    case Tonemap::None:
    case Tonemap::Clamp:
        for (float& v : linear) v = clamp01(v);
        return linear;
    case Tonemap::PbrNeutral: {
        Rgb out = tonemap_pbr_neutral(linear);
        for (float& v : out) v = clamp01(v);
        return out;
    }
    case Tonemap::Agx: return tonemap_agx(linear);
    case Tonemap::Aces: return tonemap_aces(linear);
    }
    return linear;
}

bool is_identity(const DisplayTransform& display)
{
    return display.tonemap == Tonemap::None || (display.tonemap == Tonemap::Clamp && display.exposure_ev == 0.0f);
}

Film to_display_linear(const Film& film, const DisplayTransform& display)
{
    Film out = film;
    if (is_identity(display)) return out;
    std::vector<float>& data = out.data();
    for (size_t i = 0; i < data.size(); i += 4) {
        const Rgb c = apply_display_transform(display, {data[i], data[i + 1], data[i + 2]});
        data[i] = c[0];
        data[i + 1] = c[1];
        data[i + 2] = c[2];
    }
    return out;
}

}  // namespace gc
