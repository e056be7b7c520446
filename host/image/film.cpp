#include "host/image/film.h"

#include <cassert>
#include <limits>

#include "host/util/error.h"

namespace gc {

Film::Film(uint32_t width, uint32_t height) : m_width(width), m_height(height)
{
    // Say which size was asked for instead of a bare std::length_error from the vector.
    const size_t limit = std::numeric_limits<size_t>::max() / (4 * sizeof(float));
    if (width != 0 && size_t(height) > limit / width)
        throw InputError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is too large");
    m_data.assign(size_t(width) * height * 4, 0.0f);
    for (size_t i = 3; i < m_data.size(); i += 4) m_data[i] = 1.0f;
}

size_t Film::index(uint32_t x, uint32_t y) const
{
    assert(x < m_width && y < m_height);
    return (size_t(y) * m_width + x) * 4;
}

Rgba Film::at(uint32_t x, uint32_t y) const
{
    const float* p = pixel(x, y);
    return {p[0], p[1], p[2], p[3]};
}

void Film::set(uint32_t x, uint32_t y, const Rgba& c)
{
    float* p = pixel(x, y);
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
    p[3] = c.a;
}

void Film::fill(const Rgba& c)
{
    for (size_t i = 0; i < m_data.size(); i += 4) {
        m_data[i] = c.r;
        m_data[i + 1] = c.g;
        m_data[i + 2] = c.b;
        m_data[i + 3] = c.a;
    }
}

}  // namespace gc
