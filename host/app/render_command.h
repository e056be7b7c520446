// `geocold-cl SCENE`: load, build, render with progress, write. Returns the exit code.
#pragma once

#include <string>
#include <vector>

#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {

ExitCode run_render(const Options& options);
ExitCode run_list_devices();
// `geocold-cl merge PART.exr... -o FRAME.exr [--spp N]`: partial images into the frame.
ExitCode run_merge(const std::vector<std::string>& args);

}  // namespace gc
