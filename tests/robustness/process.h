// Runs the real geocold-cl executable as a child process and collects what a user would see:
// the exit status (or the signal that killed it), stdout, stderr and the wall time.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gc::test {

struct RunOptions {
    std::map<std::string, std::string> env;      // set (or, with an empty value, unset) in the child
    std::filesystem::path cwd;                    // empty = the test's own working directory
    std::optional<unsigned long long> max_file_size;  // RLIMIT_FSIZE in bytes; SIGXFSZ is ignored
    std::optional<unsigned long long> max_address_space;  // RLIMIT_AS in bytes
    double timeout_seconds = 300.0;               // then SIGKILL: a hang is a failure
};

struct RunResult {
    int exit_code = -1;      // valid when signal == 0
    int signal = 0;          // the signal that ended the child, 0 = it exited
    bool timed_out = false;
    std::string out;
    std::string err;
    double seconds = 0.0;

    // "exit 3" / "killed by signal 6 (Aborted)" / "timed out"
    std::string describe() const;
    // Lines of stderr containing `needle`.
    int count_err_lines(const std::string& needle) const;
};

// Runs `program args...`, stdin from /dev/null.
RunResult run_process(const std::filesystem::path& program, const std::vector<std::string>& args,
                      const RunOptions& options = {});

// Runs the child on a pseudo-terminal (so it draws its progress bar), calls `on_output` with
// everything read so far each time more arrives (it may send the child signals), and returns
// when the child has exited. `out` holds the terminal output; `err` stays empty.
RunResult run_on_terminal(const std::filesystem::path& program, const std::vector<std::string>& args,
                          const RunOptions& options, const std::function<void(int pid, const std::string& so_far)>& on_output);

// The geocold-cl under test and the environment every run of it gets: a kernel binary cache
// shared by the tests (only the first run compiles), plus sanitizer limits in ASan builds.
std::filesystem::path cli_path();
RunOptions cli_options();

// True when `geocold-cl --list-devices` lists a CPU device (the tests render with --device cpu).
bool have_cpu_device();

// A fresh folder per test under the system temp folder, removed afterwards.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }
    std::filesystem::path operator/(const std::string& name) const { return m_path / name; }
    // Names of everything inside, sorted (to spot stray temp files).
    std::vector<std::string> entries() const;

private:
    std::filesystem::path m_path;
};

std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, const std::string& bytes);

}  // namespace gc::test
