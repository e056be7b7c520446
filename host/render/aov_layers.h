// AOV layers beside a beauty (geocold-cl --aovs): the first-hit facts of the scene, and the
// beauty's own per-pixel statistics, as the parts of one multi-part OpenEXR file.
//
//   part          channels          what
//   albedo        R, G, B  FLOAT    the aov integrator's albedo, k_aov_layer_spp samples
//   normal        X, Y, Z  FLOAT    the shading normal, world space, k_aov_layer_spp samples
//   depth         Z        FLOAT    distance along the camera ray to the first hit, 0 for a miss
//   primid        id       UINT     the scene triangle hit, 4294967295 for a miss
//   variance      R, G, B  FLOAT    the beauty's per-pixel sample variance (n - 1)
//   sample-count  N        UINT     the beauty's samples per pixel
//
// Depth and primid are the first sample's (sample index 0) values: a mean of ids, or of the
// depths either side of an edge, is no id or depth of anything in the scene. Albedo and normal
// are anti-aliased like the beauty.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "host/image/exr_writer.h"
#include "host/render/renderer.h"

namespace gc {

enum class AovLayer { Albedo, Normal, Depth, PrimitiveId, Variance, SampleCount };

inline constexpr std::uint32_t k_aov_layer_spp = 16;

const char* aov_layer_name(AovLayer layer);
// "albedo,normal,...": UsageError naming the unknown or repeated entry.
std::vector<AovLayer> parse_aov_layers(const std::string& list);
std::string aov_layer_names();  // "albedo, normal, ..." for messages and --help

// Whether the layer comes from the beauty's squared sums (the chunks must carry them).
inline bool needs_squares(AovLayer layer) { return layer == AovLayer::Variance; }

// One AOV rendered with `like`'s device, scene, camera, size and seed by the aov integrator.
Film render_aov_like(const Renderer& like, AovKind kind, std::uint32_t spp);

// The layers as EXR parts, in the order asked. `beauty` is the frame's sums (with squares
// when a layer needs them); `like` a renderer of the beauty's scene on some device.
std::vector<ExrPart> render_aov_layers(const Renderer& like, const FilmSums& beauty,
                                       const std::vector<AovLayer>& layers);

}  // namespace gc
