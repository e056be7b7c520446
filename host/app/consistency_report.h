// The figures of `geocold-cl --consistency` and how they are judged: pure functions of
// images, so tests check them on hand-made films without a device.
//
// Every pair of renders (same scene, camera, seed, spp, resolution; different devices) is
// compared on R, G and B:
//   rel_mse  mean over pixels and channels of (b - a)^2 / (a^2 + 1e-2): the relative MSE of
//            tests/data/refs/README.md (host/image/compare.h), the 1e-2 keeping black pixels
//            from dominating;
//   max_abs  the largest |b - a| over pixels and channels;
//   within   the fraction of pixels whose every channel satisfies
//                |b - a| <= pixel_rel_tol * max(|a|, |b|)   or   |b - a| <= pixel_abs_tol
//            (symmetric in a and b: neither device is the reference; the absolute floor only
//            matters for black and near-black pixels). A pixel with a NaN/Inf is outside.
//   identical  pixels whose RGB are bit-identical in both (reported, not judged).
// A pair passes when rel_mse <= max_rel_mse and within >= min_within, and the images are not
// black (a black comparison proves nothing) and have no NaN/Inf.
//
// Why two figures and no limit on max_abs: devices differ in the last ulps of sin, cos, pow
// and exp (OpenCL C allows 4 to 16 ulp). Most paths only move by those ulps, but now and then
// a perturbed path takes another branch (Russian roulette's threshold, the other side of an
// edge, another lobe) and from then on is an unrelated sample. Such a pixel's mean moves by
// (sample difference) / spp, far beyond 1e-3 relative, while the image's relative MSE stays
// tiny. So `within` counts those rare pixels and `rel_mse` bounds their weight; max_abs is
// shown to explain them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "host/image/film.h"

namespace gc {

struct ConsistencyTolerances {
    double max_rel_mse = 1e-5;     // issue 5: NVIDIA vs PoCL, Cornell box, 64 spp
    double min_within = 0.999;     // fraction of pixels
    double pixel_rel_tol = 1e-3;
    double pixel_abs_tol = 1e-6;
};

// One render of the comparison: which device made it, and how long it took.
struct ConsistencyRender {
    std::string api;       // "opencl" or "vulkan"
    std::string device;    // device name
    std::string platform;  // OpenCL platform and driver version; empty for Vulkan (device says it all)
    double seconds = 0.0;  // render wall time (kernel build excluded)
    Film image;
};

struct ConsistencyPair {
    std::size_t a = 0;  // indices into the render list
    std::size_t b = 0;
    std::size_t pixels = 0;
    std::size_t nonfinite = 0;  // pixels with a NaN/Inf in either image
    std::size_t identical = 0;  // pixels whose RGB bits agree
    double rel_mse = 0.0;
    double max_abs = 0.0;
    double within = 0.0;
    double mean_a = 0.0;  // mean RGB value of each image
    double mean_b = 0.0;
    bool passed = false;
    std::string why;      // empty when passed; else which limit failed
};

// Throws InputError when the sizes differ or the images are empty.
ConsistencyPair compare_renders(const Film& a, const Film& b, const ConsistencyTolerances& tol = {});

// Every pair (i < j) of renders.
std::vector<ConsistencyPair> compare_all(const std::vector<ConsistencyRender>& renders,
                                         const ConsistencyTolerances& tol = {});

struct ConsistencyRun {
    std::string scene;
    std::string integrator;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t spp = 0;
    std::uint32_t seed = 0;
    ConsistencyTolerances tolerances;
    std::vector<ConsistencyRender> renders;
    std::vector<ConsistencyPair> pairs;
    std::vector<std::string> notes;  // e.g. "Vulkan: not available (...)"

    bool skipped() const { return renders.size() < 2; }
    bool passed() const;  // every pair passed (true when skipped: nothing failed)
};

// The text report: a legend of the devices, then one line per pair with its figures and
// "pass"/"FAIL", then a verdict line ("consistency: PASSED ...", "consistency: FAILED ..." or
// "consistency: SKIPPED ..." when fewer than two devices rendered).
std::string format_report(const ConsistencyRun& run);

// The same as JSON (an object; see the keys in the .cpp). Images are not included.
std::string format_json(const ConsistencyRun& run);

// "scene-stem_0-vs-1" style file-name stem for a pair's heat map.
std::string heatmap_stem(const ConsistencyRun& run, const ConsistencyPair& pair);

}  // namespace gc
