// The Vulkan commands of the CLI: `--preview` (the rasterised mesh pass to an image) and
// `--cross-check vulkan` (OpenCL vs Vulkan figures). In a build without Vulkan both throw
// UsageError("this build has no Vulkan support").
#pragma once

#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {

ExitCode run_preview(const Options& options);
ExitCode run_cross_check(const Options& options);

}  // namespace gc
