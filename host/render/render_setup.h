// How a front end runs the renderer on a device, apart from what to render (RenderSettings):
// the speed knobs and where the kernels and their binary cache are. None of it changes the image.
#pragma once

#include "host/cl/program.h"
#include "host/render/device_tuning.h"

namespace gc {

struct RenderSetup {
    DeviceTuning tuning;
    cl::BuildConfig build;  // empty kernel_dir: the built-in search; empty cache_dir: no cache
};

}  // namespace gc
