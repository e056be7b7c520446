#include "tools/bench/bench_environment.h"

#include <cstdlib>
#include <string>

#include "host/app/environment.h"
#include "host/util/error.h"

namespace gc::bench {
namespace {

RenderSetup read_setup()
{
    RenderSetup setup = render_setup_from_environment();
    if (const char* grid = std::getenv("GEOCOLD_WAVEFRONT_GRID"); grid && *grid) {
        const std::string value(grid);
        bool allowed = false;
        for (const char* a : {"0", "1", "64", "256", "512", "1024", "2048", "4096", "8192"})
            allowed = allowed || value == a;
        if (!allowed)
            throw UsageError("GEOCOLD_WAVEFRONT_GRID must be 0, 1, 64, 256, 512, 1024, 2048, 4096 or "
                             "8192, not '" + value + "'");
        setup.tuning.wavefront_items_per_unit = static_cast<std::uint32_t>(std::stoul(value));
    }
    if (const char* sync = std::getenv("GEOCOLD_WAVEFRONT_SYNC"); sync && *sync)
        setup.tuning.wavefront_sync_counts = sync[0] != '0';
    return setup;
}

}  // namespace

const RenderSetup& bench_render_setup()
{
    static const RenderSetup setup = read_setup();
    return setup;
}

}  // namespace gc::bench
