// Checks on a loaded scene that do not depend on its file format: load_scene runs them after
// whichever loader read the file.
#pragma once

#include <cstdint>
#include <string>

#include "host/scene/scene.h"

namespace gc {

// True when the triangle's corners are collinear or coincide. The cross product is taken in
// double, where products of float coordinates neither underflow (a scene 1e-30 across) nor
// overflow (1e30 across): in float either would make a real triangle look flat.
bool has_zero_area(const Point3& p0, const Point3& p1, const Point3& p2);

// Throws InputError naming the scene's file when every triangle has zero area: no ray can
// hit any of them, so the image could only be empty. Degenerate triangles among real ones
// are kept (files have them).
void check_some_triangle_has_area(const Scene& scene);

// The scales the single-precision kernels render correctly, measured on the Cornell box
// scaled from 1e-15 to 1e30 (docs/design.md): the triangle test multiplies three coordinate
// differences, which overflow float's range past ~1e13 and lose their precision to
// underflow below ~1e-13, so the image goes dark. Inside these limits the image does not
// change with the scale (tests/stress).
inline constexpr double kLargestRenderableCoordinate = 1e12;
inline constexpr double kSmallestRenderableSize = 1e-12;

// Throws InputError naming the scene's file and its extent when its coordinates reach past
// kLargestRenderableCoordinate or its largest side is below kSmallestRenderableSize: such a
// scene would render dark or black, and the fix (scaling it) is the user's to make.
void check_renderable_scale(const Scene& scene);

// Limits on a flat scene's triangles: 2^27 (the device keeps ~200 bytes per triangle, so
// 25 GiB), and what the host's memory can take while loading, building the BVH and (on a CPU
// device, whose buffers are host memory) rendering: a 2M-triangle mesh peaked at 1.16 GB
// resident rendering on PoCL, ~480 bytes per triangle, rounded up.
inline constexpr std::uint64_t kMaxFlatTriangles = std::uint64_t{1} << 27;
inline constexpr std::uint64_t kHostBytesPerFlatTriangle = 512;

// The machine's physical memory in bytes (the largest value when it cannot be read).
std::uint64_t physical_memory_bytes();
// "12.3 GiB".
std::string gibibytes(std::uint64_t bytes);
// Whether `triangles` fit the limits above; else `why` says how much memory they would need.
bool flat_triangles_fit(std::uint64_t triangles, std::string& why);

}  // namespace gc
