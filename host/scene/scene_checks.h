// Checks on a loaded scene that do not depend on its file format: load_scene runs them after
// whichever loader read the file.
#pragma once

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

}  // namespace gc
