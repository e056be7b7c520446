// geocold-bench's command line: what to measure, where, and how long.
#pragma once

#include <string>
#include <vector>

namespace gc::bench {

struct Options {
    std::string device = "all";
    std::vector<std::string> scenes;
    bool quick = false;
    bool json_out = false;
    int repeats = 5;
    int ray_side = 1024;
    bool path = true;
    bool packet_probe = true;
    bool rays = true;
    bool first_image = true;
    int threads = 0;                           // --threads: 0 = every core
    int wavefront = 0;                         // --wavefront: paths in flight per pass, 0 = the renderer's default
    int samples_per_pass = 0;                  // --samples-per-pass: a fixed count, 0 = the renderer's plan
    std::string first_image_child;             // the device key (device_key()) in the child process
    std::string first_image_scene = "cornell"; // and the scene it renders
    bool list_device_keys = false;             // child: print "<label>\t<key>" per selected device
};

// Parses argv; --help prints the usage and exits 0. Throws UsageError for an unknown option
// or a bad value.
Options parse_options(int argc, char** argv);

}  // namespace gc::bench
