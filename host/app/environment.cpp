#include "host/app/environment.h"

#include <cstdlib>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "host/cl/binary_cache.h"
#include "host/cl/program.h"
#include "host/util/error.h"

namespace gc {
namespace {

// The variable's value; "" when unset.
std::string variable(const char* name)
{
    const char* value = std::getenv(name);
    return value ? value : "";
}

// The value of `name` when set, after checking it is one of `allowed`; nullopt when unset or
// empty. `allowed_text` is how the message lists the choices, e.g. "'scene' or 'all'".
std::optional<std::string> choice(const char* name, std::initializer_list<std::string_view> allowed,
                                  const char* allowed_text)
{
    const std::string value = variable(name);
    if (value.empty()) return std::nullopt;
    for (const std::string_view a : allowed)
        if (value == a) return value;
    throw UsageError(std::string(name) + " must be " + allowed_text + ", not '" + value + "'");
}

DeviceTuning tuning_from_environment()
{
    DeviceTuning tuning;
    if (const auto width = choice("GEOCOLD_BVH_WIDTH", {"2", "4", "8"}, "2, 4 or 8"))
        tuning.bvh_layout =
            *width == "8" ? BvhLayout::Wide8 : (*width == "4" ? BvhLayout::Wide : BvhLayout::Binary);
    if (const auto set = choice("GEOCOLD_KERNEL_FEATURES", {"scene", "all"}, "'scene' or 'all'"))
        tuning.kernel_features = *set == "all" ? KernelFeatureSet::All : KernelFeatureSet::Scene;
    if (const auto form =
            choice("GEOCOLD_PATH_KERNEL", {"wavefront", "megakernel"}, "'wavefront' or 'megakernel'"))
        tuning.path_kernel =
            *form == "megakernel" ? PathKernelForm::Megakernel : PathKernelForm::Wavefront;
    return tuning;
}

cl::BuildConfig build_config_from_environment()
{
    cl::BuildConfig build;
    build.kernel_dir = variable("GEOCOLD_KERNEL_DIR");
    // Checked here too, so that the message names the variable the user set.
    if (!build.kernel_dir.empty() && !cl::is_kernel_dir(build.kernel_dir))
        throw DeviceError("GEOCOLD_KERNEL_DIR=" + build.kernel_dir.string() +
                          " is not a geocold-cl kernel directory (no shared/gc_types.h in it)");
    build.use_cache = variable("GEOCOLD_NO_CACHE") != "1";
    if (const std::string dir = variable("GEOCOLD_CACHE_DIR"); !dir.empty()) {
        build.cache_dir = dir;
    } else if (const auto user =
                   cl::user_cache_dir(variable("XDG_CACHE_HOME"), variable("HOME"))) {
        build.cache_dir = *user;
    }
    build.store_when_driver_caches = variable("GEOCOLD_CACHE_ALWAYS").starts_with('1');
    // PoCL's own switch for its kernel cache: with it off, ours is the only cache left.
    build.driver_cache_disabled = variable("POCL_KERNEL_CACHE").starts_with('0');
    return build;
}

}  // namespace

RenderSetup render_setup_from_environment()
{
    return {tuning_from_environment(), build_config_from_environment()};
}

std::filesystem::path image_module_from_environment()
{
    return variable("GEOCOLD_IMAGE_MODULE");
}

std::filesystem::path oidn_library_from_environment()
{
    return variable("GEOCOLD_OIDN_LIBRARY");
}

}  // namespace gc
