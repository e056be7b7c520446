// Ctrl-C handling: the first SIGINT asks the render loop to stop after the current sample
// and write what it has; a second one ends the process at once.
#pragma once

namespace gc {

void install_interrupt_handler();
// The same for SIGTERM (a farm's scheduler stopping a task): the render stops at its next pass.
void install_termination_handler();
bool interrupt_requested();

}  // namespace gc
