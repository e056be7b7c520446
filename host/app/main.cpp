// geocold-cl: the command-line renderer. Turns every failure into one message on stderr and
// the exit code documented in --help.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "host/app/consistency_command.h"
#include "host/app/options.h"
#include "host/app/render_command.h"
#include "host/app/vk_commands.h"
#include "host/util/error.h"
#include "host/util/log.h"

int main(int argc, char** argv)
{
    using namespace gc;
    try {
        const Options options = parse_options(std::vector<std::string>(argv + 1, argv + argc));
        if (options.help) {
            std::fputs(usage_text().c_str(), stdout);
            return 0;
        }
        if (options.version) {
            std::puts(version_text().c_str());
            return 0;
        }
        set_log_level(options.quiet ? LogLevel::Quiet : (options.verbose ? LogLevel::Verbose : LogLevel::Normal));
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
