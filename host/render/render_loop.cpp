#include "host/render/render_loop.h"

#include <chrono>

#include "host/render/pass_planner.h"

namespace gc {

RenderOutcome render_to(Renderer& renderer, std::uint32_t spp, const RenderControl& control)
{
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const bool limited = control.time_limit_seconds > 0.0;
    RenderOutcome outcome;
    while (renderer.samples_done() < spp) {
        std::uint32_t wanted = spp - renderer.samples_done();
        // The CPU's passes grow to two seconds in long renders: cut to the deadline.
        if (limited)
            wanted = samples_before_deadline(control.time_limit_seconds - elapsed(), renderer.seconds_per_sample(), wanted);
        renderer.render_samples(wanted);
        if (control.on_pass) control.on_pass(renderer.samples_done());
        if (control.cancelled && control.cancelled()) {
            outcome.cancelled = true;
            break;
        }
        if (limited && elapsed() >= control.time_limit_seconds && renderer.samples_done() < spp) {
            outcome.timed_out = true;
            break;
        }
    }
    outcome.samples = renderer.samples_done();
    outcome.seconds = elapsed();
    return outcome;
}

}  // namespace gc
