// geocold-cl --aovs: the AOV layers (aov_layers.h) rendered after the beauty and written as one
// multi-part OpenEXR beside it, with the project's own EXR writer (the bare build writes them
// too, whatever the beauty's format).
#pragma once

#include <filesystem>
#include <vector>

#include "host/cl/device.h"
#include "host/image/film.h"
#include "host/render/aov_layers.h"
#include "host/render/render_setup.h"
#include "host/render/session.h"

namespace gc {

// "<output without its extension>.aovs.exr", beside the output.
std::filesystem::path aov_layers_path(const std::filesystem::path& output);

// Renders `layers` on `device` for the beauty `beauty` (its frame's sums; squares when a
// layer needs them) and writes them, atomically, to aov_layers_path(output).
void write_aov_layers(const std::vector<AovLayer>& layers, const cl::DeviceInfo& device, const PreparedScene& prepared,
                      const RenderSettings& settings, const RenderSetup& setup, const FilmSums& beauty,
                      const ImageMetadata& meta, const std::filesystem::path& output);

}  // namespace gc
