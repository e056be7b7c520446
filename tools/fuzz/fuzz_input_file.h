// Hands a fuzzer's bytes to a loader that only takes a path: one scratch file per process,
// rewritten for every input, in a RAM-backed folder (/dev/shm) when there is one, so the
// loaders' real file-reading code is what gets fuzzed without touching the disk.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace gc::fuzz {

class InputFile {
public:
    explicit InputFile(const std::string& file_name)
    {
        std::error_code ec;
        std::filesystem::path root = "/dev/shm";
        if (!std::filesystem::is_directory(root, ec)) root = std::filesystem::temp_directory_path();
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
    std::filesystem::path m_dir;
    std::filesystem::path m_path;
};

}  // namespace gc::fuzz
