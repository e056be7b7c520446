// How far the OpenCL and Vulkan first-hit images are apart (primitive ids, depth, the edge
// rule), and the cross-check's limits; radiance is compared by host/image/compare.h. Pure
// functions of images, so they are tested on hand-made inputs without any device.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gc_types.h"
#include "host/image/compare.h"
#include "host/image/film.h"
#include "host/scene/scene.h"

namespace gc::vk {

// 1/64 pixel: four steps of an 8-bit sub-pixel grid (vertex snapping moves an edge by at
// most half a step), so drivers with coarser snapping than lavapipe still pass.
inline constexpr double kDefaultEdgePixels = 1.0 / 64.0;

// The edge rule. Rasterisation and ray casting both sample the pixel centre, but decide
// which triangle owns a centre lying (almost) on a triangle's edge by different rounding:
// fixed-point edge functions after vertex snapping to 1/256 pixel (Vulkan's usual
// subPixelPrecisionBits = 8) against the watertight float test. So a pixel is an edge pixel
// when its centre lies within `edge_px` pixels of an edge of the triangle that EITHER image
// shows there (a triangle crossing the camera plane counts as near everywhere). A
// disagreement anywhere else is a real one. (A 3x3-neighbourhood rule would exclude every
// pixel of a mesh whose triangles are about a pixel in size, e.g. the Stanford bunny.)
// Returns one flag (0/1) per pixel, row-major; ids are scene triangle indices, -1 = none.
std::vector<std::uint8_t> edge_pixels(const Scene& scene, const dev::GcCamera& camera,
                                      const std::vector<std::int32_t>& ref_ids,
                                      const std::vector<std::int32_t>& test_ids, std::uint32_t width,
                                      std::uint32_t height, double edge_px = kDefaultEdgePixels);

// Where triangle `tri` projects: the image position (pixels, x right, y down, pixel centres at
// +0.5) of its corners under `camera`; false when a corner is not in front of the camera.
bool project_triangle(const Scene& scene, const dev::GcCamera& camera, std::uint32_t width, std::uint32_t height,
                      std::size_t tri, double xy[3][2]);

struct IdDepthAgreement {
    std::size_t covered = 0;       // pixels where either image has a triangle
    std::size_t edge_excluded = 0; // covered pixels left out by the edge rule (`exclude`)
    std::size_t compared = 0;      // covered - edge_excluded
    std::size_t equal_ids = 0;     // compared pixels with the same id
    double id_agreement = 1.0;     // equal_ids / compared (1 when nothing is compared)
    double max_depth_rel_error = 0.0;  // over compared pixels with equal ids: |d_test - d_ref| / d_ref
    double mean_depth_rel_error = 0.0;
};

// ids: -1 = background. depth: distance along the pixel-centre ray where ids are >= 0.
// exclude: one flag per pixel (edge_pixels), or empty to compare every covered pixel.
IdDepthAgreement compare_ids_depth(const std::vector<std::int32_t>& ref_ids, const std::vector<float>& ref_depth,
                                   const std::vector<std::int32_t>& test_ids, const std::vector<float>& test_depth,
                                   const std::vector<std::uint8_t>& exclude);

// The pass/fail limits of the cross-check (DESIGN.md "Cross-checks").
struct Tolerances {
    double min_id_agreement = 0.995;
    double max_depth_rel_error = 1e-4;
    AgreementLimits radiance{1e-4, 0.99};  // looser than the consistency check's AgreementLimits{}
};

// Ids from a primitive-id AOV film (the red channel holds the id as a float, -1 = miss).
std::vector<std::int32_t> ids_from_film(const Film& film);
// The red channel of a depth AOV film.
std::vector<float> depth_from_film(const Film& film);

}  // namespace gc::vk
