#include "host/image/srgb.h"

#include <cmath>

namespace gc {

float srgb_encode(float linear)
{
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded)
{
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

uint8_t linear_to_srgb8(float linear)
{
    // NaN fails both comparisons: map it to black rather than to an arbitrary byte.
    const float c = linear > 0.0f ? std::fmin(linear, 1.0f) : 0.0f;
    return uint8_t(std::lround(srgb_encode(c) * 255.0f));
}

}  // namespace gc
