// The geocold-cl command line as a function: parses `args` (argv without the program name),
// runs the command, prints every failure as one message on stderr and returns the exit code
// documented in --help. main.cpp calls it; so does `python -m geocold`.
#pragma once

#include <string>
#include <vector>

namespace gc {

int run_cli(const std::vector<std::string>& args);

}  // namespace gc
