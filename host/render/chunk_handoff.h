// Takes a finished chunk's sums off a device without holding the device up. The chunk's film
// is copied on the device into a staging film, in the render queue's order (so before the
// film is cleared for the next chunk); a second queue reads the copy to the host and the
// delivery (the frame's addition) runs on a thread of its own, while the render queue goes on
// with the next chunk. Without it a GPU idled for the read-back and the host's addition of
// every chunk (docs/performance.md, "Several devices on one frame").
//
// One delivery is in flight at a time: the next hand_off waits for the last, and so does
// wait(), which also rethrows its error. The delivered sums are the bits Renderer::sums would
// have read at the hand-off.
#pragma once

#include <functional>
#include <future>

#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/render/renderer.h"

namespace gc {

class ChunkHandoff {
public:
    using Delivery = std::function<void(FilmSums&&)>;

    // Staging films for `renderer`'s image, with squares if `with_squares`.
    ChunkHandoff(const cl::Context& context, const Renderer& renderer, bool with_squares);
    // Waits for the delivery in flight; its error, if any, is dropped (call wait() to see it).
    ~ChunkHandoff();
    ChunkHandoff(const ChunkHandoff&) = delete;
    ChunkHandoff& operator=(const ChunkHandoff&) = delete;

    // Waits for the last delivery (rethrowing its error), enqueues the copy of `renderer`'s
    // film as it is now, and starts `deliver` with its sums once they are on the host.
    void hand_off(const Renderer& renderer, Delivery deliver);
    // Waits for the delivery in flight, if any, and rethrows its error.
    void wait();

private:
    const cl::Context& m_context;
    cl_command_queue m_read_queue = nullptr;
    cl::Buffer<glm::vec4> m_sums;
    cl::Buffer<glm::vec4> m_squares;
    bool m_with_squares;
    std::future<void> m_in_flight;
};

}  // namespace gc
