#include "process.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace gc::test {

namespace {

using Clock = std::chrono::steady_clock;

// argv and envp for execve, built before fork (the child only calls async-signal-safe code).
struct ExecArgs {
    std::vector<std::string> argv_storage;
    std::vector<std::string> env_storage;
    std::vector<char*> argv;
    std::vector<char*> envp;

    ExecArgs(const std::filesystem::path& program, const std::vector<std::string>& args, const RunOptions& options)
    {
        argv_storage.push_back(program.string());
        argv_storage.insert(argv_storage.end(), args.begin(), args.end());
        for (char** e = environ; *e; ++e) {
            const std::string entry = *e;
            const std::string key = entry.substr(0, entry.find('='));
            if (!options.env.count(key)) env_storage.push_back(entry);
        }
        for (const auto& [key, value] : options.env)
            if (!value.empty()) env_storage.push_back(key + "=" + value);
        for (std::string& s : argv_storage) argv.push_back(s.data());
        argv.push_back(nullptr);
        for (std::string& s : env_storage) envp.push_back(s.data());
        envp.push_back(nullptr);
    }
};

// In the child, after fork: limits, folder, then exec. Never returns.
[[noreturn]] void exec_child(const ExecArgs& exec, const RunOptions& options)
{
    if (!options.cwd.empty() && ::chdir(options.cwd.c_str()) != 0) ::_exit(126);
    if (options.max_file_size) {
        // Writes past the limit then fail with EFBIG, as on a full disk, instead of killing.
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{*options.max_file_size, *options.max_file_size};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
    }
    if (options.max_address_space) {
        const rlimit limit{*options.max_address_space, *options.max_address_space};
        if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
    }
    std::signal(SIGINT, SIG_DFL);
    ::execve(exec.argv[0], exec.argv.data(), exec.envp.data());
    ::_exit(127);
}

void finish_wait(pid_t pid, RunResult& result)
{
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
}

}  // namespace

std::string RunResult::describe() const
{
    if (timed_out) return "timed out (killed)";
    if (signal) return "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
    return "exit " + std::to_string(exit_code);
}

int RunResult::count_err_lines(const std::string& needle) const
{
    int n = 0;
    std::istringstream lines(err);
    std::string line;
    while (std::getline(lines, line))
        if (line.find(needle) != std::string::npos) ++n;
    return n;
}

RunResult run_process(const std::filesystem::path& program, const std::vector<std::string>& args,
                      const RunOptions& options)
{
    const ExecArgs exec(program, args, options);
    int out_pipe[2], err_pipe[2];
    if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    const auto start = Clock::now();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        const int null_fd = ::open("/dev/null", O_RDONLY);
        if (null_fd < 0 || ::dup2(null_fd, 0) < 0 || ::dup2(out_pipe[1], 1) < 0 || ::dup2(err_pipe[1], 2) < 0) ::_exit(126);
        exec_child(exec, options);
    }
    ::close(out_pipe[1]);
    ::close(err_pipe[1]);

    RunResult result;
    pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
    std::string* sinks[2] = {&result.out, &result.err};
    int open_fds = 2;
    while (open_fds > 0) {
        const double left = options.timeout_seconds - std::chrono::duration<double>(Clock::now() - start).count();
        if (left <= 0) {
            result.timed_out = true;
            ::kill(pid, SIGKILL);
            break;
        }
        const int ready = ::poll(fds, 2, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
        if (ready < 0 && errno != EINTR) break;
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buffer[4096];
            const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
            if (n > 0) {
                sinks[i]->append(buffer, static_cast<std::size_t>(n));
            } else if (n == 0 || errno != EINTR) {
                ::close(fds[i].fd);
                fds[i].fd = -1;
                --open_fds;
            }
        }
    }
    for (pollfd& f : fds)
        if (f.fd >= 0) ::close(f.fd);
    finish_wait(pid, result);
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

RunResult run_on_terminal(const std::filesystem::path& program, const std::vector<std::string>& args,
                          const RunOptions& options, const std::function<void(int, const std::string&)>& on_output)
{
    const ExecArgs exec(program, args, options);
    const auto start = Clock::now();
    int master = -1;
    winsize size{};
    size.ws_row = 24;
    size.ws_col = 100;
    const pid_t pid = ::forkpty(&master, nullptr, nullptr, &size);
    if (pid < 0) throw std::runtime_error("forkpty failed");
    if (pid == 0) exec_child(exec, options);

    RunResult result;
    for (;;) {
        const double left = options.timeout_seconds - std::chrono::duration<double>(Clock::now() - start).count();
        if (left <= 0) {
            result.timed_out = true;
            ::kill(pid, SIGKILL);
            break;
        }
        pollfd fd{master, POLLIN, 0};
        const int ready = ::poll(&fd, 1, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
        if (ready < 0 && errno != EINTR) break;
        if (ready <= 0) continue;
        char buffer[4096];
        const ssize_t n = ::read(master, buffer, sizeof buffer);
        if (n > 0) {
            result.out.append(buffer, static_cast<std::size_t>(n));
            on_output(pid, result.out);
        } else if (n == 0 || errno != EINTR) {
            break;  // EIO: the child closed the terminal (it exited)
        }
    }
    ::close(master);
    finish_wait(pid, result);
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

std::filesystem::path cli_path() { return GC_CLI_PATH; }

RunOptions cli_options()
{
    RunOptions options;
    options.env["GEOCOLD_CACHE_DIR"] = GC_ROBUSTNESS_CACHE_DIR;
    options.env["GEOCOLD_NO_CACHE"] = "";
    // Our cache even on PoCL (which otherwise relies on its own kcache): a run under a file-size
    // limit must find every compiled kernel already on disk, and PoCL rewrites kcache files
    // when it builds from source.
    options.env["GEOCOLD_CACHE_ALWAYS"] = "1";
#if defined(__SANITIZE_ADDRESS__)
    // A hostile count must fail as an error, not grind through tens of GB under ASan.
    const char* asan = std::getenv("ASAN_OPTIONS");
    options.env["ASAN_OPTIONS"] = std::string(asan ? asan : "") + (asan && *asan ? ":" : "") + "max_allocation_size_mb=8192";
#endif
    return options;
}

bool have_cpu_device()
{
    static const bool have = [] {
        RunOptions options = cli_options();
        options.timeout_seconds = 120;
        const RunResult r = run_process(cli_path(), {"--list-devices"}, options);
        const bool found = r.exit_code == 0 && r.signal == 0 && r.out.find("cpu") != std::string::npos;
        if (!found) std::printf("  no OpenCL CPU device (%s): %s\n", r.describe().c_str(), r.err.c_str());
        return found;
    }();
    return have;
}

TempDir::TempDir()
{
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    m_path = std::filesystem::temp_directory_path() / ("gc_robust_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(m_path);
    std::filesystem::create_directories(m_path);
}

TempDir::~TempDir()
{
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
}

std::vector<std::string> TempDir::entries() const
{
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(m_path)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string read_file(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_file(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

}  // namespace gc::test
