#include "host/render/environment.h"

#include <cmath>
#include <string>

#include "gc_sampling.h"
#include "host/image/image_io.h"
#include "host/util/error.h"

namespace gc {
namespace {

// Inclusive prefix sums of `weights`, normalised so the last entry is exactly 1; a zero row
// becomes uniform (it is never chosen by the marginal anyway, and stays a valid cdf).
void append_cdf(const std::vector<double>& weights, std::vector<float>& out)
{
    double total = 0.0;
    for (double w : weights) total += w;
    out.push_back(0.0f);
    double running = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        running += total > 0.0 ? weights[i] : 1.0;
        const double denominator = total > 0.0 ? total : static_cast<double>(weights.size());
        out.push_back(i + 1 == weights.size() ? 1.0f : static_cast<float>(running / denominator));
    }
}

}  // namespace

EnvironmentMap make_environment_map(const Film& image)
{
    EnvironmentMap map;
    const std::uint32_t w = image.width();
    const std::uint32_t h = image.height();
    if (w == 0 || h == 0) return map;
    std::vector<double> row_weights(h, 0.0);
    std::vector<std::vector<double>> texel_weights(h, std::vector<double>(w, 0.0));
    double total = 0.0;
    for (std::uint32_t y = 0; y < h; ++y) {
        const double sin_theta = std::sin(3.14159265358979323846 * (y + 0.5) / h);
        for (std::uint32_t x = 0; x < w; ++x) {
            const Rgba c = image.at(x, y);
            texel_weights[y][x] = dev::gc_luminance(dev::make_float3(c.r, c.g, c.b)) * sin_theta;
            row_weights[y] += texel_weights[y][x];
        }
        total += row_weights[y];
    }
    if (!(total > 0.0)) return map;
    map.width = w;
    map.height = h;
    map.pixels.reserve(static_cast<std::size_t>(w) * h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            const Rgba c = image.at(x, y);
            map.pixels.emplace_back(c.r, c.g, c.b, 0.0f);
        }
    append_cdf(row_weights, map.marginal_cdf);
    for (std::uint32_t y = 0; y < h; ++y) append_cdf(texel_weights[y], map.conditional_cdf);
    return map;
}

EnvironmentMap load_environment_map(const std::filesystem::path& path)
{
    const Film image = read_image(path);
    for (float v : image.data())
        if (!std::isfinite(v) || v < 0.0f)
            throw InputError(path.string() + ": environment map has non-finite or negative texels");
    EnvironmentMap map = make_environment_map(image);
    map.source = path.string();
    return map;
}

EnvironmentMap load_environment_map(const RenderSettings& settings)
{
    return settings.env_map_path.empty() ? EnvironmentMap{} : load_environment_map(settings.env_map_path);
}

}  // namespace gc
