// Time to first image: a fresh process loads a bench scene (or generates it), builds the BVH,
// creates the context, lays the scene out on the device, builds (or loads) the path program,
// renders one sample of the scene's path view and reads the film back. Cold: empty
// GEOCOLD_CACHE_DIR, POCL_CACHE_DIR and CUDA_CACHE_PATH; warm: the same directories again.
// Runs in a child process because the driver caches live in the process (and PoCL reads
// POCL_CACHE_DIR once).
#pragma once

#include <string>
#include <vector>

#include "host/cl/device.h"

namespace gc::bench {

struct FirstImage {
    bool ok = false;
    bool skipped = false;         // the scene's file is missing (error says which)
    std::string error;
    double process_seconds = 0.0; // the child's whole life, as the parent saw it
    double total_seconds = 0.0;   // inside the child: start of main to film in host memory
    double scene_seconds = 0.0;   // loading (or generating) the scene and building its BVH
    double upload_seconds = 0.0;  // the device's BVH layout and scene buffers
    double compile_seconds = 0.0; // Program build (or cache load)
    double render_seconds = 0.0;  // first sample + film read-back
    double devices_seconds = 0.0; // listing the OpenCL devices (loads every platform's driver)
    double context_seconds = 0.0; // the context and queue on the chosen device
    bool from_cache = false;
};

// Names `device` among `devices` (what list_devices() gave) so that another process finds the
// same device: platform name, device name and the ordinal among devices that share both. Not
// the list index: a process may see another list (a GPU that another process holds in
// exclusive compute mode is left out or reported unavailable, and the loader's platform
// order is not promised), and an index then names another device or none.
std::string device_key(const cl::DeviceInfo& device, const std::vector<cl::DeviceInfo>& devices);

// Runs the child for bench scene `scene` (load_bench_scene's names) on the device named by
// `key` (device_key) with the three cache variables pointing under cache_root (which must
// exist). The caller must hold no context on the device: the child measures a device it has
// to itself.
FirstImage run_first_image(const std::string& key, const std::string& scene, const std::string& cache_root);

// The child's side: renders, prints one line
// "first-image <total> <compile> <render> <cached> <devices> <context> <scene> <upload>" on
// stdout. Returns the process exit code: 0, 2 when no device matches the key (said on stderr
// with the devices this process sees), kFirstImageSceneMissing when the scene's file is not
// there (said on stdout).
int first_image_child(const std::string& key, const std::string& scene);
constexpr int kFirstImageSceneMissing = 3;

}  // namespace gc::bench
