// The sRGB transfer functions (IEC 61966-2-1). Shared by the built-in writers and the
// OpenImageIO module (which compiles its own copy of srgb.cpp: it links nothing of gc_image).
#pragma once

#include <cstdint>

namespace gc {

// On [0, 1].
float srgb_encode(float linear);
float srgb_decode(float encoded);
// Clamp to [0, 1] (NaN -> 0), encode, round to 8 bits.
uint8_t linear_to_srgb8(float linear);

}  // namespace gc
