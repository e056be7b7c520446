// A measuring aid, not part of geocold-cl: an LD_PRELOAD library that rewrites the options
// of every clBuildProgram call, so the cost and the effect of the strict-math build options
// can be measured on any driver without rebuilding the program.
//   GEOCOLD_SHIM_REMOVE="opt ..."  drops these options (e.g. -cl-fp32-correctly-rounded-divide-sqrt)
//   GEOCOLD_SHIM_ADD="opt ..."     appends these (e.g. -cl-denorms-are-zero, -cl-fast-relaxed-math)
// Use with GEOCOLD_NO_CACHE=1: the kernel binary cache keys on the options geocold-cl asked
// for, so a cached binary would hide the rewrite.
//   g++ -std=c++20 -shared -fPIC -O2 -I .deps/include tools/device/cl_options_shim.cpp -o shim.so -ldl
//   LD_PRELOAD=$PWD/shim.so GEOCOLD_NO_CACHE=1 GEOCOLD_SHIM_REMOVE=... geocold-cl ...
// GEOCOLD_SHIM_DUMP=<folder> also writes each built program's binary there (program-N.bin, the
// build's order; PTX on NVIDIA, for `ptxas -v`: registers, stack frame and spills per kernel).
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <dlfcn.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> words(const char* text)
{
    std::vector<std::string> out;
    std::istringstream in(text ? text : "");
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

// Option strings from geocold-cl are space-separated words (include paths are quoted only
// when they contain spaces, which the shim leaves alone: it only drops exact words).
std::string rewrite(const char* options)
{
    const std::vector<std::string> remove = words(std::getenv("GEOCOLD_SHIM_REMOVE"));
    std::string out;
    for (const std::string& w : words(options)) {
        bool drop = false;
        for (const std::string& r : remove) drop = drop || w == r;
        if (!drop) out += (out.empty() ? "" : " ") + w;
    }
    for (const std::string& w : words(std::getenv("GEOCOLD_SHIM_ADD"))) out += (out.empty() ? "" : " ") + w;
    return out;
}

// Writes the program's binary for its first device to GEOCOLD_SHIM_DUMP/program-N.bin.
void dump_binary(cl_program program)
{
    static std::atomic<int> count{0};
    const char* folder = std::getenv("GEOCOLD_SHIM_DUMP");
    if (!folder) return;
    size_t size = 0;
    if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr) != CL_SUCCESS || size == 0)
        return;
    std::vector<unsigned char> binary(size);
    unsigned char* pointers[1] = {binary.data()};
    if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof pointers, pointers, nullptr) != CL_SUCCESS) return;
    const std::string path = std::string(folder) + "/program-" + std::to_string(count++) + ".bin";
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(binary.data(), 1, binary.size(), f);
        std::fclose(f);
    }
}

}  // namespace

extern "C" CL_API_ENTRY cl_int CL_API_CALL clBuildProgram(cl_program program, cl_uint num_devices,
                                                          const cl_device_id* device_list, const char* options,
                                                          void(CL_CALLBACK* notify)(cl_program, void*),
                                                          void* user_data)
{
    using Fn = cl_int(CL_API_CALL*)(cl_program, cl_uint, const cl_device_id*, const char*,
                                    void(CL_CALLBACK*)(cl_program, void*), void*);
    static const Fn next = reinterpret_cast<Fn>(dlsym(RTLD_NEXT, "clBuildProgram"));
    if (!next) return CL_INVALID_OPERATION;
    const std::string rewritten = rewrite(options);
    if (std::getenv("GEOCOLD_SHIM_VERBOSE")) std::fprintf(stderr, "cl_options_shim: %s\n", rewritten.c_str());
    const cl_int status = next(program, num_devices, device_list, rewritten.c_str(), notify, user_data);
    if (status == CL_SUCCESS) dump_binary(program);
    return status;
}
