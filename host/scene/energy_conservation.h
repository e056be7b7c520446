// Material rules shared by the loaders.
#pragma once

#include "host/scene/scene.h"

namespace gc {

// The modified Phong BRDF f = kd/pi + ks (n+2)/(2 pi) cos^n(alpha) conserves energy only when
// kd + ks <= 1 per channel (Lafortune and Willems 1994, "Using the modified Phong reflectance
// model for physically based rendering"). Where a channel exceeds 1, both kd and ks of that
// channel are scaled by 1/(kd+ks), which keeps their ratio. Returns true when it changed anything.
bool enforce_energy_conservation(Material& material);

}  // namespace gc
