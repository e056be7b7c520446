// `geocold-cl SCENE`: load, build, render with progress, write. Returns the exit code.
#pragma once

#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {

ExitCode run_render(const Options& options);
ExitCode run_list_devices();

}  // namespace gc
