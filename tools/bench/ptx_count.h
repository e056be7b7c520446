// Static instruction counts of the kernels in an NVIDIA PTX module: the instruction half of
// geocold-bench's GPU roofline needs to know what a unit of traversal compiles to, and
// NVIDIA's OpenCL driver hands out PTX text as a program's binary.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace gc::bench {

// True when `binary` is PTX text (a `.version` and a `.target sm_` directive), which is what
// NVIDIA's OpenCL returns for CL_PROGRAM_BINARIES; other drivers return objects or bitcode.
bool looks_like_ptx(std::string_view binary);

// Instruction statements per function (`.entry` kernels and `.func`s), each call counting
// its callee's statements as well (recursively; a recursive call counts once), so a kernel's
// figure is what one pass through all of its code would issue. Directives (`.reg`, `.loc`,
// ...), labels, braces and comments are not instructions. Functions that are only declared
// are absent.
std::map<std::string, int> count_ptx_instructions(std::string_view ptx);

}  // namespace gc::bench
