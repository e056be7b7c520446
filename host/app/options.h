// The geocold-cl command line: parsing, validation and the --help text. Parsing never
// touches files or devices; it only turns argv into Options or throws UsageError.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "host/image/display_transform.h"
#include "host/math/affine.h"
#include "host/render/aov_layers.h"
#include "host/render/render_settings.h"
#include "host/render/session.h"

namespace gc {

struct Options {
    std::string scene_path;
    std::string output_path;     // empty = "<scene stem>.png" in the current directory
    std::string device = "any";
    bool list_devices = false;
    bool help = false;
    bool version = false;
    bool quiet = false;
    bool verbose = false;
    int gltf_scene = -1;         // -1 = the file's default scene
    bool flatten_instances = false;  // --flatten-instances: no two-level BVH for reused glTF meshes
    bool spp_given = false;
    bool env_scale_given = false;
    bool preview = false;         // --preview: the Vulkan raster pass instead of a render
    std::string cross_check;      // --cross-check API: "vulkan", or empty
    std::string vk_device = "any"; // --vk-device: any | lavapipe | <name substring>
    bool consistency = false;     // --consistency: render on every device, compare the pairs
    std::string json_path;        // --json FILE: the consistency report as JSON
    std::string heatmap_dir;      // --heatmap DIR: a difference heat map per device pair
    bool res_given = false;       // --res / --width / --height given (consistency's default is 128x128)
    int threads = 0;              // --threads: CPU threads (host and PoCL); 0 = every core
    // --samples A:B: render samples [A, B) into a partial image (host/render/partial_image.h)
    bool partial = false;
    std::uint32_t samples_first = 0;
    std::uint32_t samples_end = 0;
    std::uint32_t chunk_samples = 64;  // --chunk-samples: the frame's canonical chunk size
    std::string resume_path;          // --resume FILE: go on from a checkpoint (resumable_frame.h)
    double checkpoint_seconds = 0.0;  // --checkpoint-every SEC; 0: no checkpoints
    std::vector<AovLayer> aovs;       // --aovs: layers written beside the output (aov_layers.h)
    std::optional<Tonemap> tonemap;   // --tonemap: 8-bit outputs' curve (default: pbr-neutral; none for AOVs)
    std::optional<float> exposure_ev; // --exposure EV: 8-bit outputs are scaled by 2^EV first
    bool denoise = false;         // --denoise: Open Image Denoise on the beauty, with albedo/normal guides

    RenderSettings render;

    std::optional<Point3> look_from;
    std::optional<Point3> look_at;
    std::optional<Vec3> up;
    std::optional<float> fov_degrees;
    std::optional<float> aperture_radius;  // --aperture R: thin-lens depth of field
    std::optional<float> focus_distance;   // --focus-distance D (default: to --look-at)
};

// Throws UsageError with a message that names the offending option and value.
Options parse_options(const std::vector<std::string>& args);

// The scene file, its glTF scene and the camera overrides the options name.
SceneRequest scene_request(const Options& options);

std::string usage_text();

// --device all, or a comma-separated list: one frame on several devices.
bool names_several_devices(const std::string& device_spec);
std::string version_text();

}  // namespace gc
