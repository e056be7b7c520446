// A linear-RGBA float image: what the renderer accumulates into and what the writers
// consume. Row 0 is the top of the image (the refs' convention); pixels are stored row-major
// as four floats each, so data() can be handed to an image library or a device buffer as is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gc {

// What a written image records about how it was made (EXR attributes "geocold:*").
struct ImageMetadata {
    std::string device;      // e.g. "NVIDIA H100 (OpenCL 3.0 CUDA)"
    std::string integrator;  // path, whitted, aov
    std::string scene;       // the scene file as given on the command line
    uint32_t spp = 0;
    double seconds = 0.0;    // render wall time
    uint32_t seed = 0;
};

struct Rgba {
    float r = 0, g = 0, b = 0, a = 1;
    bool operator==(const Rgba&) const = default;
};

class Film {
public:
    Film() = default;
    // A black, opaque (alpha 1) image. Throws InputError when width * height * 4 does not fit.
    Film(uint32_t width, uint32_t height);

    uint32_t width() const { return m_width; }
    uint32_t height() const { return m_height; }
    size_t pixel_count() const { return size_t(m_width) * m_height; }
    bool empty() const { return m_width == 0 || m_height == 0; }

    // Unchecked in release builds (asserted in debug): the render loop calls these per pixel.
    Rgba at(uint32_t x, uint32_t y) const;
    void set(uint32_t x, uint32_t y, const Rgba& c);
    float* pixel(uint32_t x, uint32_t y) { return m_data.data() + index(x, y); }
    const float* pixel(uint32_t x, uint32_t y) const { return m_data.data() + index(x, y); }

    // Every pixel to c.
    void fill(const Rgba& c);

    // width * height * 4 floats, RGBA interleaved, top row first.
    std::vector<float>& data() { return m_data; }
    const std::vector<float>& data() const { return m_data; }

    bool operator==(const Film&) const = default;

private:
    size_t index(uint32_t x, uint32_t y) const;

    uint32_t m_width = 0;
    uint32_t m_height = 0;
    std::vector<float> m_data;
};

}  // namespace gc
