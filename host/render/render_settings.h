// What to render: everything the command line can say about a render, independent of the
// scene and the device.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

namespace gc {

enum class IntegratorKind { Aov, Path, Whitted };
enum class AovKind { Preview, Albedo, Normal, Depth, PrimitiveId, GuideAlbedo, GuideNormal };
// Where a sample's random numbers come from (kernels/shared/gc_rng.h): Owen-scrambled Sobol
// points (the default: lower error at the same spp; docs/decisions/sobol-sampler.md), or
// independent hashes.
enum class SamplerKind { Independent, Sobol };

struct RenderSettings {
    int width = 512;
    int height = 512;
    std::uint32_t spp = 64;
    std::uint32_t seed = 0;
    SamplerKind sampler = SamplerKind::Sobol;
    std::uint32_t max_depth = 8;       // path segments (Mitsuba's convention): 1 = emitters only
    std::uint32_t rr_depth = 5;        // Russian roulette from this depth on
    double time_limit_seconds = 0.0;   // 0 = none; otherwise stop after the pass that crosses it
    IntegratorKind integrator = IntegratorKind::Path;
    AovKind aov = AovKind::Preview;
    glm::vec3 env_radiance{0.0f};      // constant environment, or the scale of env_map_path
    std::string env_map_path;          // lat-long environment map (.exr/.hdr/.pfm); empty = none
    std::uint32_t wavefront_size = 0;  // paths in flight per pass; 0 = chosen for the device
    // Path integrator: at most this many samples per pixel in one pass; 0 = chosen by the
    // renderer (host/render/pass_planner.h on CPUs, as many as the wavefront holds on GPUs).
    std::uint32_t samples_per_pass = 0;
    // Adaptive sampling (host/render/adaptive.h): a pixel stops once the relative standard
    // error of its mean is below this, spp being the cap; 0 = off (every pixel gets spp).
    double noise_threshold = 0.0;
};

inline const char* integrator_name(IntegratorKind k)
{
    switch (k) {
    case IntegratorKind::Aov: return "aov";
    case IntegratorKind::Path: return "path";
    case IntegratorKind::Whitted: return "whitted";
    }
    return "?";
}

inline const char* aov_name(AovKind k)
{
    switch (k) {
    case AovKind::Preview: return "preview";
    case AovKind::Albedo: return "albedo";
    case AovKind::Normal: return "normal";
    case AovKind::Depth: return "depth";
    case AovKind::PrimitiveId: return "primid";
    case AovKind::GuideAlbedo: return "guide-albedo";
    case AovKind::GuideNormal: return "guide-normal";
    }
    return "?";
}

// The kinds the names above name (front ends parse their users' words with these); nullopt
// for any other word.
inline std::optional<IntegratorKind> integrator_from_name(std::string_view name)
{
    for (IntegratorKind k : {IntegratorKind::Aov, IntegratorKind::Path, IntegratorKind::Whitted})
        if (name == integrator_name(k)) return k;
    return std::nullopt;
}

inline const char* sampler_name(SamplerKind k) { return k == SamplerKind::Sobol ? "sobol" : "independent"; }

inline std::optional<SamplerKind> sampler_from_name(std::string_view name)
{
    for (SamplerKind k : {SamplerKind::Independent, SamplerKind::Sobol})
        if (name == sampler_name(k)) return k;
    return std::nullopt;
}

inline std::optional<AovKind> aov_from_name(std::string_view name)
{
    for (AovKind k : {AovKind::Preview, AovKind::Albedo, AovKind::Normal, AovKind::Depth, AovKind::PrimitiveId,
                      AovKind::GuideAlbedo, AovKind::GuideNormal})
        if (name == aov_name(k)) return k;
    return std::nullopt;
}

}  // namespace gc
