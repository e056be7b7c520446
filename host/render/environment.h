// A lat-long environment map and the 2D piecewise-constant distribution that importance-
// samples it (luminance times sin(theta), so texels near the poles, which cover less solid
// angle, are chosen less): the host half of kernels/shared/gc_lights.h.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host/image/film.h"
#include "host/render/render_settings.h"

namespace gc {

struct EnvironmentMap {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec4> pixels;      // linear RGB; row 0 is the zenith (+Y)
    std::vector<float> marginal_cdf;    // height + 1 entries, 0 ... 1
    std::vector<float> conditional_cdf; // height rows of width + 1 entries, each 0 ... 1
    std::string source;                 // the file it was read from; empty when made in memory

    bool empty() const { return width == 0 || height == 0; }
};

// Builds the sampling distribution of an image. A black image gives an empty map (the
// environment is then black and never sampled).
EnvironmentMap make_environment_map(const Film& image);

// Reads a lat-long map (.exr, .hdr, .pfm, ...): InputError naming the file on failure or on
// non-finite or negative texels.
EnvironmentMap load_environment_map(const std::filesystem::path& path);

// The map --env names (settings.env_map_path), or an empty one when it names none.
EnvironmentMap load_environment_map(const RenderSettings& settings);

}  // namespace gc
