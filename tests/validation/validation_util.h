// Helpers shared by the validation tests: render a scene to a mean and a per-sample variance,
// and where to leave images when a comparison fails.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>

#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/image/film.h"
#include "host/image/image_io.h"
#include "host/render/render_settings.h"
#include "host/render/renderer.h"
#include "host/scene/scene.h"

// The Mitsuba references are EXR files, which only a build with OpenImageIO reads. A bare
// build (GEOCOLD_WITH_OIIO=OFF, the GPU node's) skips the tests that need them; a build with
// it always runs them.
#if defined(GC_HAVE_OIIO)
#define GC_SKIP_WITHOUT_EXR_READER() ((void)0)
#else
#define GC_SKIP_WITHOUT_EXR_READER() \
    GTEST_SKIP() << "the references are EXR files and this build has no OpenImageIO (GEOCOLD_WITH_OIIO=OFF)"
#endif

namespace gc::validation {

struct Rendered {
    Film mean;
    Film variance;  // per-sample variance (n - 1 denominator)
    double seconds = 0.0;
};

inline Rendered render(const cl::Context& context, const Scene& scene, const Camera& camera,
                       const RenderSettings& settings, const RenderSetup& setup = {})
{
    const FlatBvh bvh = build_bvh(scene);
    Renderer renderer(context, scene, bvh, camera, settings, setup);
    const auto start = std::chrono::steady_clock::now();
    for (std::uint32_t k = 0; k < settings.spp; ++k) renderer.render_sample();
    Rendered out;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.mean = renderer.film();
    out.variance = renderer.variance();
    return out;
}

// The references' view of the Cornell boxes (tests/data/refs/cornell-*.json).
inline Camera cornell_camera()
{
    Camera camera;
    camera.look_from = Point3(0, 1, 3.9f);
    camera.look_at = Point3(0, 1, 0);
    camera.vfov_degrees = 39.3077f;
    return camera;
}

// Failing comparisons leave their images beside the test binary (GC_TEST_OUTPUT_DIR), where
// CI artifacts and a developer both find them.
inline std::filesystem::path failure_path(const std::string& file_name)
{
    return std::filesystem::path(GC_TEST_OUTPUT_DIR) / file_name;
}

}  // namespace gc::validation
