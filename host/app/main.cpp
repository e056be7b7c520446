// geocold-cl: the command-line renderer (host/app/cli.h). Turns every failure into one message
// on stderr and the exit code documented in --help.
#include <string>
#include <vector>

#include "host/app/cli.h"

int main(int argc, char** argv)
{
    return gc::run_cli(std::vector<std::string>(argv + 1, argv + argc));
}
