// The loop every front end runs around a Renderer: passes until the sample count, a time
// limit or a cancellation, with a report after each pass.
#pragma once

#include <cstdint>
#include <functional>

#include "host/render/renderer.h"

namespace gc {

struct RenderControl {
    // Seconds from the loop's start; 0: none. A pass is cut to what fits before it, so the
    // render stops at most about one sample's time late.
    double time_limit_seconds = 0.0;
    // Asked after each pass; true ends the render with the film intact (Ctrl-C).
    std::function<bool()> cancelled;
    // Called after each pass with the film's sample count (progress bars).
    std::function<void(std::uint32_t samples_done)> on_pass;
};

struct RenderOutcome {
    std::uint32_t samples = 0;  // the film's sample count at the end
    double seconds = 0.0;       // the loop's wall time
    bool cancelled = false;
    bool timed_out = false;
};

// Renders until the film holds `spp` samples (continuing from what it holds) or `control`
// stops it.
RenderOutcome render_to(Renderer& renderer, std::uint32_t spp, const RenderControl& control = {});

}  // namespace gc
