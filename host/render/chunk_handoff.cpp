#include "host/render/chunk_handoff.h"

#include <utility>

#include "host/cl/error.h"

namespace gc {
namespace {

cl::Buffer<glm::vec4> staging_film(const cl::Context& context, const Renderer& renderer, const char* name)
{
    const RenderSettings& s = renderer.settings();
    const std::size_t pixels = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
    return cl::Buffer<glm::vec4>::create(context, pixels, CL_MEM_READ_WRITE, name);
}

// Owns an event until the end of the scope.
struct EventRelease {
    cl_event event;
    ~EventRelease()
    {
        if (event) clReleaseEvent(event);
    }
};

}  // namespace

ChunkHandoff::ChunkHandoff(const cl::Context& context, const Renderer& renderer, bool with_squares)
    : m_context(context),
      m_sums(staging_film(context, renderer, "staging film")),
      m_with_squares(with_squares)
{
    if (with_squares) m_squares = staging_film(context, renderer, "staging film squares");
    m_read_queue = GC_CL_CREATE("creating the read-back queue on " + context.device().device_name,
                                clCreateCommandQueue, context.context(), context.device().id, 0);
}

ChunkHandoff::~ChunkHandoff()
{
    try {
        wait();
    } catch (...) {  // NOLINT(bugprone-empty-catch): the owner that wanted the error called wait()
    }
    clReleaseCommandQueue(m_read_queue);
}

void ChunkHandoff::wait()
{
    if (!m_in_flight.valid()) return;
    std::future<void> last = std::move(m_in_flight);
    last.get();
}

void ChunkHandoff::hand_off(const Renderer& renderer, Delivery deliver)
{
    wait();
    FilmSums header;
    EventRelease copied{renderer.copy_sums(m_sums, m_with_squares ? &m_squares : nullptr, header)};
    // Submitted now, not at the render queue's next wait: the read waits for the copy.
    GC_CL_WHAT("submitting the film's copy", clFlush, m_context.queue());
    const auto read = [this](const cl::Buffer<glm::vec4>& from, std::vector<glm::vec4>& to, cl_event after) {
        to.resize(from.count());
        GC_CL_WHAT("reading '" + from.name() + "' on " + m_context.device().device_name, clEnqueueReadBuffer,
                   m_read_queue, from.mem(), CL_TRUE, 0, from.bytes(), to.data(), 1, &after, nullptr);
    };
    cl_event after = copied.event;
    m_in_flight = std::async(std::launch::async, [this, read, after, header = std::move(header),
                                                  deliver = std::move(deliver)]() mutable {
        EventRelease release{after};
        read(m_sums, header.sums, after);
        if (m_with_squares) read(m_squares, header.squares, after);
        deliver(std::move(header));
    });
    copied.event = nullptr;  // the delivery releases it
}

}  // namespace gc
