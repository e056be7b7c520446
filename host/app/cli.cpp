#include "host/app/cli.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "host/app/consistency_command.h"
#include "host/app/environment.h"
#include "host/app/options.h"
#include "host/app/render_command.h"
#include "host/app/vk_commands.h"
#include "host/cl/device.h"
#include "host/image/image_module.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"
#include "host/util/log.h"

namespace gc {

int run_cli(const std::vector<std::string>& args)
{
    try {
        if (!args.empty() && args[0] == "merge") {
#ifdef GC_HAVE_OIIO
            set_image_module_path(image_module_from_environment());
#endif
            return static_cast<int>(run_merge(std::vector<std::string>(args.begin() + 1, args.end())));
        }
        const Options options = parse_options(args);
        if (options.help) {
            std::fputs(usage_text().c_str(), stdout);
            return 0;
        }
        if (options.version) {
            std::puts(version_text().c_str());
            return 0;
        }
#ifdef GC_HAVE_OIIO
        // Before anything reads or writes an image: the module is found once per process.
        // (A build without OpenImageIO has no module: its formats are built in.)
        set_image_module_path(image_module_from_environment());
#endif
        set_log_level(options.quiet ? LogLevel::Quiet : (options.verbose ? LogLevel::Verbose : LogLevel::Normal));
        if (options.threads > 0) {
            // Before any OpenCL or Vulkan call: PoCL reads its thread count when it is first
            // loaded, lavapipe (LP_NUM_THREADS) when its device is created.
            set_host_thread_count(options.threads);
            cl::limit_cpu_device_threads(options.threads);
            setenv("LP_NUM_THREADS", std::to_string(options.threads).c_str(), 1);
        } else if (names_several_devices(options.device)) {
            // One frame on several devices: the CPU device leaves cores to the host threads
            // that drive the others (PoCL reads the limit when it is loaded, so before any
            // OpenCL call, and before we know whether there is a GPU). Two from 8 cores on: a
            // thread waiting for an NVIDIA GPU spins, and the chunks' sums are added on the
            // host, so one core was not enough (docs/performance.md).
            const int cores = static_cast<int>(std::thread::hardware_concurrency());
            if (cores > 1) cl::limit_cpu_device_threads(cores >= 8 ? cores - 2 : cores - 1);
        }
        if (options.list_devices) return static_cast<int>(run_list_devices());
        if (options.preview) return static_cast<int>(run_preview(options));
        if (!options.cross_check.empty()) return static_cast<int>(run_cross_check(options));
        if (options.consistency) return static_cast<int>(run_consistency(options));
        return static_cast<int>(run_render(options));
    } catch (const UsageError& e) {
        std::fprintf(stderr, "geocold-cl: %s\nTry 'geocold-cl --help' for more information.\n", e.what());
        return static_cast<int>(ExitCode::Usage);
    } catch (const Error& e) {
        std::fprintf(stderr, "geocold-cl: error: %s\n", e.what());
        return static_cast<int>(e.code());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "geocold-cl: error: out of host memory\n");
        return static_cast<int>(ExitCode::Internal);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geocold-cl: internal error: %s\n", e.what());
        return static_cast<int>(ExitCode::Internal);
    }
}

}  // namespace gc
