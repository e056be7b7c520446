// The report of `geocold-cl --consistency`: which devices rendered, and how each pair of
// renders (same scene, camera, seed, spp, resolution; different devices) agrees. The figures
// and the pass rule are host/image/compare.h's (compare_images, judge_agreement under
// AgreementLimits); this file only arranges and formats them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "host/image/compare.h"
#include "host/image/film.h"

namespace gc {

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
    ImageDifference diff;  // b measured against a (a is the relative metrics' reference)
    AgreementVerdict verdict;
};

// Every pair (i < j) of renders. Throws InputError when the sizes differ or the images are empty.
std::vector<ConsistencyPair> compare_all(const std::vector<ConsistencyRender>& renders,
                                         const AgreementLimits& limits = {});

struct ConsistencyRun {
    std::string scene;
    std::string integrator;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t spp = 0;
    std::uint32_t seed = 0;
    AgreementLimits tolerances;
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
