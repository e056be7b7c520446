// The benchmark's generated large scene: a deterministic field of bumpy spheres on a ground
// plane under a square area light, built in memory (no big files in the repository).
#pragma once

#include <cstdint>

#include "host/scene/scene.h"

namespace gc::bench {

// Spheres: `grid` x `grid` icospheres subdivided `levels` times (20 * 4^levels triangles
// each), radially displaced by a sum of sines whose phases come from a fixed integer hash,
// on a 2-triangle ground plane, lit by a 2-triangle emitter above. grid 8, levels 6 gives
// 64 * 81 920 + 4 = 5 242 884 triangles. The same arguments give the same bits everywhere:
// only +, -, *, / and std::sqrt (correctly rounded) enter a vertex position, and the
// displacement's sines are evaluated in double and rounded once.
Scene make_large_mesh(int grid = 8, int levels = 6);

}  // namespace gc::bench
