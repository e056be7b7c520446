// Display transforms: how linear radiance becomes the display-referred values that 8-bit
// outputs (PNG, PPM, 8-bit OIIO formats) then encode with the sRGB OETF. Float outputs
// (EXR, PFM, HDR, TIFF) are written linear and never pass through here.
//
//   none         the film's values as they are (the sRGB encoding clips them to [0, 1]);
//                no exposure (three.js NoToneMapping)
//   clamp        exposure, then the clip (three.js LinearToneMapping; Blender "Standard")
//   pbr-neutral  exposure, then the Khronos PBR Neutral tone mapper (KhronosGroup/ToneMapping,
//                PBR_Neutral/README.md): base colours below 0.8 pass unchanged, highlights
//                compress and desaturate towards white. The CLI's default for beauty PNGs.
//   agx          exposure, then AgX (Troy Sobotka, sobotka/AgX; Blender's default view): the
//                inset matrix and [-12.47393, 4.026069] EV log encoding of the minimal
//                implementation (Wrensch, iolite-engine.com "Minimal AgX Implementation"),
//                with the sigmoid in its closed form (bWFuanVzYWth/AgX), the outset matrix
//                and the 2.2 display EOTF back to display-linear
//   aces         exposure, then Narkowicz's 2016 per-channel fit of the ACES RRT + sRGB ODT
//                ("ACES Filmic Tone Mapping Curve"): x(2.51x+0.03)/(x(2.43x+0.59)+0.14)
//
// Every curve maps linear Rec. 709 to display-linear Rec. 709 in [0, 1]; exposure multiplies
// by 2^EV first. NaN and negative inputs count as 0. Alpha is not touched.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "host/image/film.h"

namespace gc {

enum class Tonemap { None, Clamp, PbrNeutral, Agx, Aces };

struct DisplayTransform {
    Tonemap tonemap = Tonemap::Clamp;  // the library's default: exposure 0 and a clip, as before
    float exposure_ev = 0.0f;
};

using Rgb = std::array<float, 3>;

// "none", "clamp", "pbr-neutral", "agx", "aces"; nullopt for anything else.
std::optional<Tonemap> parse_tonemap(std::string_view name);
const char* tonemap_name(Tonemap tonemap);
// "none|clamp|pbr-neutral|agx|aces", for messages.
const char* tonemap_names();

// The curves alone (no exposure), on non-negative linear input.
Rgb tonemap_pbr_neutral(Rgb c);
Rgb tonemap_agx(Rgb c);
Rgb tonemap_aces(Rgb c);
// AgX's sigmoid on its log-encoded input in [0, 1] (display-encoded output in [0, 1]).
float agx_sigmoid(float x);

// Exposure and curve for one colour: display-linear, in [0, 1] except for `none`.
Rgb apply_display_transform(const DisplayTransform& display, Rgb linear);

// The film with the transform applied to every pixel's RGB.
Film to_display_linear(const Film& film, const DisplayTransform& display);

// True when the transform changes nothing (none, or clamp at 0 EV: the encoders clip anyway).
bool is_identity(const DisplayTransform& display);

}  // namespace gc
