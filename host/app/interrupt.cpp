#include "host/app/interrupt.h"

#include <csignal>
#include <unistd.h>

namespace gc {
namespace {

volatile std::sig_atomic_t g_interrupts = 0;

extern "C" void on_sigint(int signal)
{
    g_interrupts = g_interrupts + 1;
    if (g_interrupts == 1) {
        static const char message[] = "\ngeocold-cl: interrupted; finishing the current sample and writing the image "
                                      "(Ctrl-C again to quit now)\n";
        const ssize_t ignored = write(STDERR_FILENO, message, sizeof message - 1);
        (void)ignored;
    } else {
        std::signal(signal, SIG_DFL);
        std::raise(signal);
    }
}

}  // namespace

void install_interrupt_handler() { std::signal(SIGINT, on_sigint); }
void install_termination_handler() { std::signal(SIGTERM, on_sigint); }
bool interrupt_requested() { return g_interrupts > 0; }

}  // namespace gc
