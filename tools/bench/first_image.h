// Time to first image: a fresh process loads the Cornell box, builds the BVH, creates the
// context, builds (or loads) the wavefront program, renders one sample and reads the film
// back. Cold: empty GEOCOLD_CACHE_DIR, POCL_CACHE_DIR and CUDA_CACHE_PATH; warm: the same
// directories again. Runs in a child process because the driver caches live in the process
// (and PoCL reads POCL_CACHE_DIR once).
#pragma once

#include <string>

namespace gc::bench {

struct FirstImage {
    bool ok = false;
    std::string error;
    double process_seconds = 0.0; // the child's whole life, as the parent saw it
    double total_seconds = 0.0;   // inside the child: start of main to film in host memory
    double compile_seconds = 0.0; // Program build (or cache load)
    double render_seconds = 0.0;  // first sample + film read-back
    bool from_cache = false;
};

// Runs the child for `device_index` with the three cache variables pointing under
// cache_root (which must exist). `tiny`: 64x64 instead of 512x512.
FirstImage run_first_image(int device_index, const std::string& cache_root, bool tiny);

// The child's side: renders, prints one line "first-image <total> <compile> <render> <cached>"
// on stdout. Returns the process exit code.
int first_image_child(int device_index, bool tiny);

}  // namespace gc::bench
