#include "host/cl/program.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "host/cl/binary_cache.h"
#include "host/cl/error.h"
#include "host/util/log.h"

namespace gc::cl {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw DeviceError("cannot read kernel source " + path.string());
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Quoted only when needed: drivers split options on spaces, and not all of them honour quotes.
std::string include_option(const fs::path& dir)
{
    const std::string text = dir.string();
    return text.find(' ') == std::string::npos ? "-I " + text : "-I \"" + text + "\"";
}

// The folder of the test and bench probes (kernels/test): a product program never includes
// them, so their edits must not change the product programs' hash (and every user's cache).
constexpr const char* kProbeFolder = "test";

bool is_probe(const fs::path& relative)
{
    return relative.begin() != relative.end() && *relative.begin() == kProbeFolder;
}

// Hash of every kernel source that could be #included, in a stable order: the product sources,
// and the probes' too when a probe is being built. Hashing too much only costs a rebuild;
// missing an input would reuse a stale binary.
std::uint64_t hash_kernel_sources(const fs::path& kernel_dir, bool with_probes)
{
    std::vector<std::pair<std::string, fs::path>> sources;
    for (const auto& entry : fs::recursive_directory_iterator(kernel_dir)) {
        const std::string ext = entry.path().extension().string();
        const fs::path relative = fs::relative(entry.path(), kernel_dir);
        if (entry.is_regular_file() && (ext == ".cl" || ext == ".h") && (with_probes || !is_probe(relative)))
            sources.emplace_back(relative.generic_string(), entry.path());
    }
    std::sort(sources.begin(), sources.end());
    Fnv1a hash;
    hash.add_field("geocold-cl kernel sources v1");
    for (const auto& [name, path] : sources) {
        hash.add_field(name);
        hash.add_field(read_text(path));
    }
    return hash.value();
}

// The options carry the source hash, so this covers the sources too.
std::uint64_t compute_cache_key(const std::string& file, const std::string& options,
                                const DeviceInfo& device)
{
    Fnv1a hash;
    hash.add_field("geocold-cl program cache v1");
    for (const std::string* field : {&file, &options, &device.device_name, &device.driver_version,
                                     &device.platform_version, &device.device_version}) {
        hash.add_field(*field);
    }
    return hash.value();
}

std::string build_log(cl_program program, cl_device_id device)
{
    size_t size = 0;
    if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) !=
        CL_SUCCESS)
        return {};
    std::string log(size, '\0');
    if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr) !=
        CL_SUCCESS) {
        return {};
    }
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n' || log.back() == ' '))
        log.pop_back();
    return log;
}

std::vector<unsigned char> program_binary(cl_program program)
{
    size_t size = 0;
    GC_CL_WHAT("reading a program binary", clGetProgramInfo, program, CL_PROGRAM_BINARY_SIZES,
               sizeof size, &size, nullptr);
    std::vector<unsigned char> binary(size);
    unsigned char* data = binary.data();
    if (size > 0) {
        GC_CL_WHAT("reading a program binary", clGetProgramInfo, program, CL_PROGRAM_BINARIES,
                   sizeof data, &data, nullptr);
    }
    return binary;
}

// A program from a cached binary, or nullptr with the reason in `why`.
cl_program load_binary(const Context& context, const std::vector<unsigned char>& binary,
                       const std::string& options, std::string& why)
{
    const cl_device_id device = context.device().id;
    const size_t size = binary.size();
    const unsigned char* data = binary.data();
    cl_int status = CL_SUCCESS;
    cl_int err = CL_SUCCESS;
    cl_program program =
        clCreateProgramWithBinary(context.context(), 1, &device, &size, &data, &status, &err);
    if (err != CL_SUCCESS || status != CL_SUCCESS) {
        if (program) clReleaseProgram(program);
        why = format_cl_failure("clCreateProgramWithBinary", err != CL_SUCCESS ? err : status,
                                "loading the cached binary");
        return nullptr;
    }
    err = clBuildProgram(program, 1, &device, options.c_str(), nullptr, nullptr);
    if (err != CL_SUCCESS) {
        why = format_cl_failure("clBuildProgram", err, "building the cached binary") + ": " +
              build_log(program, device);
        clReleaseProgram(program);
        return nullptr;
    }
    return program;
}

// PoCL caches every build itself (kcache, keyed on the source text and the options, which
// carry GC_SOURCE_HASH) and the work-group functions it compiles at first launch, so a warm
// start is as fast without our entry. Writing one costs a lot there: clGetProgramInfo(
// CL_PROGRAM_BINARIES) makes PoCL compile a generic work-group function for every kernel on
// top of the ones the launches need, nearly doubling a cold start
// (docs/decisions/cold-start.md). With PoCL's cache
// turned off (BuildConfig::driver_cache_disabled), ours is the only one.
bool driver_caches_builds(const DeviceInfo& device, const BuildConfig& config)
{
    if (device.platform_name.find("Portable Computing Language") == std::string::npos) return false;
    return !config.driver_cache_disabled;
}

}  // namespace

bool is_kernel_dir(const fs::path& dir)
{
    std::error_code ec;
    return !dir.empty() && fs::is_regular_file(dir / "shared" / "gc_types.h", ec);
}

fs::path find_kernel_dir(const fs::path& chosen)
{
    if (!chosen.empty()) {
        if (is_kernel_dir(chosen)) return chosen;
        throw DeviceError("the kernel directory " + chosen.string() +
                          " is not a geocold-cl kernel directory (no shared/gc_types.h in it)");
    }
    std::vector<fs::path> tried;
#ifdef GEOCOLD_KERNEL_DIR
    tried.emplace_back(GEOCOLD_KERNEL_DIR);
#endif
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) tried.push_back(exe.parent_path().parent_path() / "share" / "geocold-cl" / "kernels");
    for (const fs::path& dir : tried) {
        if (is_kernel_dir(dir)) return dir;
    }
    std::string list;
    for (const fs::path& dir : tried) list += "\n  " + dir.string();
    throw DeviceError(
        "cannot find the geocold-cl kernels (shared/gc_types.h); set GEOCOLD_KERNEL_DIR. Tried:" +
        list);
}

Program::Program(const Context& context, const std::string& file, const std::string& options,
                 const BuildConfig& config)
    : m_device(context.device().id), m_device_name(context.device().device_name), m_file(file)
{
    const auto start = std::chrono::steady_clock::now();
    const DeviceInfo& device = context.device();
    const fs::path kernel_dir = find_kernel_dir(config.kernel_dir);
    const fs::path source = kernel_dir / file;
    if (!fs::is_regular_file(source))
        throw DeviceError("kernel source not found: " + source.string());

    m_options =
        include_option(kernel_dir / "shared") + " " + include_option(kernel_dir) + " -cl-std=CL1.2";
    // Strict math (never -cl-fast-relaxed-math by default). OpenCL 1.2 allows 2.5 ulp for
    // single-precision divide and 3 ulp for sqrt; asking for correct rounding where the device
    // offers it makes those results identical across devices and equal to the host's IEEE ops.
    if (device.correctly_rounded_div_sqrt) m_options += " -cl-fp32-correctly-rounded-divide-sqrt";
    // Drivers keep their own binary caches (NVIDIA's ComputeCache, PoCL's kcache), and some key
    // them on the main source text only, missing edits to #included headers. A define that
    // changes with any kernel file forces them to recompile when we do.
    m_options += " -D GC_SOURCE_HASH=0x" + to_hex(hash_kernel_sources(kernel_dir, is_probe(fs::path(file))));
    if (!options.empty()) m_options += " " + options;

    std::optional<BinaryCache> cache;
    if (config.use_cache && !config.cache_dir.empty()) cache.emplace(config.cache_dir);
    if (cache) {
        m_key = compute_cache_key(file, m_options, device);
        std::string why;
        if (auto binary = cache->load(m_key, &why)) {
            m_program = load_binary(context, *binary, m_options, why);
            if (m_program) {
                m_from_cache = true;
            } else {
                cache->remove(m_key);
            }
        }
        if (!m_program) log_verbose("building " + file + " from source (cache: " + why + ")");
    }
    if (!m_program) {
        m_program = build_from_source(context);
        if (cache && driver_caches_builds(device, config) && !config.store_when_driver_caches) {
            log_verbose("not caching " + file + ": " + device.platform_name + " keeps its own kernel cache");
        } else if (cache) {
            // Best effort: a cache that cannot be written costs the next start a compile.
            std::string why;
            try {
                if (!cache->store(m_key, program_binary(m_program), &why)) {
                    log_verbose("not caching " + file + ": " + why);
                }
            } catch (const DeviceError& e) {
                log_verbose("not caching " + file + ": " + e.what());
            }
        }
    }
    m_build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log_verbose(file + (m_from_cache ? " loaded from cache" : " compiled") + " in " +
                std::to_string(m_build_seconds) + " s on " + device.device_name);
}

cl_program Program::build_from_source(const Context& context) const
{
    // The program source is one #include of the file (found through -I <kernel dir>), so every
    // driver reports errors with the file's real path and line. Drivers name a main source
    // "<kernel>" (NVIDIA) or a temp file (PoCL), and NVIDIA ignores #line.
    const std::string text = "#include \"" + m_file + "\"\n";
    const char* data = text.c_str();
    const size_t size = text.size();
    const std::string where = "building '" + m_file + "' for " + m_device_name;
    cl_program program =
        GC_CL_CREATE(where, clCreateProgramWithSource, context.context(), 1, &data, &size);
    const cl_int err = clBuildProgram(program, 1, &m_device, m_options.c_str(), nullptr, nullptr);
    if (err != CL_SUCCESS) {
        std::string log = build_log(program, m_device);
        clReleaseProgram(program);
        throw ClBuildError(err, where + " with options '" + m_options + "'", std::move(log));
    }
    if (log_level() >= LogLevel::Verbose) {
        if (const std::string log = build_log(program, m_device); !log.empty()) {
            log_verbose("build log of " + m_file + ":\n" + log);
        }
    }
    return program;
}

Program::~Program()
{
    release();
}

Program::Program(Program&& other) noexcept
{
    *this = std::move(other);
}

Program& Program::operator=(Program&& other) noexcept
{
    if (this != &other) {
        release();
        m_program = std::exchange(other.m_program, nullptr);
        m_device = other.m_device;
        m_device_name = std::move(other.m_device_name);
        m_file = std::move(other.m_file);
        m_options = std::move(other.m_options);
        m_key = other.m_key;
        m_from_cache = other.m_from_cache;
        m_build_seconds = other.m_build_seconds;
    }
    return *this;
}

void Program::release() noexcept
{
    if (m_program) clReleaseProgram(m_program);
    m_program = nullptr;
}

std::vector<unsigned char> Program::binary() const { return program_binary(m_program); }

Kernel Program::kernel(const char* name) const
{
    cl_kernel kernel = GC_CL_CREATE(
        "creating kernel '" + std::string(name) + "' from '" + m_file + "' on " + m_device_name,
        clCreateKernel, m_program, name);
    return Kernel(kernel, name, m_device);
}

}  // namespace gc::cl
