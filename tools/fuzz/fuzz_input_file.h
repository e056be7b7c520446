// Hands a fuzzer's bytes to a loader that only takes a path: one scratch file per process,
// rewritten for every input, in a RAM-backed folder (/dev/shm) when there is one, so the
// loaders' real file-reading code is what gets fuzzed without touching the disk.
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <signal.h>
#include <unistd.h>

namespace gc::fuzz {

class InputFile {
public:
    explicit InputFile(const std::string& file_name)
    {
        std::error_code ec;
        std::filesystem::path root = "/dev/shm";
        if (!std::filesystem::is_directory(root, ec)) root = std::filesystem::temp_directory_path();
        remove_stale(root);
        m_dir = root / ("geocold-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(m_dir);
        m_path = m_dir / file_name;
    }
    ~InputFile()
    {
        std::error_code ec;
        std::filesystem::remove_all(m_dir, ec);
    }
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    // Replaces the file's contents with the input; aborts on I/O failure, which is the
    // harness's fault, not a finding in the loader.
    const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) const
    {
        std::FILE* f = std::fopen(m_path.c_str(), "wb");
        if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
            std::perror(m_path.c_str());
            std::abort();
        }
        return m_path;
    }

private:
    // A run that crashed (the point of fuzzing) never removes its folder: remove those whose
    // process is gone.
    static void remove_stale(const std::filesystem::path& root)
    {
        std::error_code ec;
        for (const auto& e : std::filesystem::directory_iterator(root, ec)) {
            const std::string name = e.path().filename().string();
            if (name.rfind("geocold-fuzz-", 0) != 0) continue;
            const long pid = std::strtol(name.c_str() + 13, nullptr, 10);
            if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) std::filesystem::remove_all(e.path(), ec);
        }
    }

    std::filesystem::path m_dir;
    std::filesystem::path m_path;
};

}  // namespace gc::fuzz
