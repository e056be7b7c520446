// Helpers shared by the tests/cl binaries: scratch directories, a throwaway kernel
// directory, and a fixture that skips when no OpenCL device is present.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/cl/context.h"
#include "host/cl/device.h"

namespace gc::cl::test {

// A fresh directory under the system temp dir, removed with everything in it.
class TempDir {
public:
    TempDir()
    {
        static std::atomic<int> counter{0};
        m_path = std::filesystem::temp_directory_path() /
                 ("gc-cl-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(m_path);
        std::filesystem::create_directories(m_path);
    }
    ~TempDir()
    {
        std::error_code ignored;
        std::filesystem::remove_all(m_path, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
};

inline void write_file(const std::filesystem::path& path, const std::string& text)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

// A kernel directory with a copy of the real kernels/shared (so it is a valid kernel dir)
// and whatever .cl files a test writes into it.
class TempKernelDir : public TempDir {
public:
    TempKernelDir()
    {
        std::filesystem::copy(std::filesystem::path(GC_TEST_SOURCE_DIR) / "kernels" / "shared",
                              path() / "shared", std::filesystem::copy_options::recursive);
    }
    void write(const std::string& name, const std::string& text) const
    {
        write_file(path() / name, text);
    }
};

// Sets an environment variable for the lifetime of the object and restores it after.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : m_name(name)
    {
        if (const char* old = std::getenv(name)) m_old = old;
        if (value)
            ::setenv(name, value, 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnv()
    {
        if (m_old)
            ::setenv(m_name.c_str(), m_old->c_str(), 1);
        else
            ::unsetenv(m_name.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    std::string m_name;
    std::optional<std::string> m_old;
};

// Device tests run on select_device($GEOCOLD_TEST_DEVICE or "any"); they skip, with the
// reason, when the machine has no OpenCL device.
class DeviceTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        std::string why;
        devices = list_devices(&why);
        if (devices.empty()) GTEST_SKIP() << "no OpenCL device: " << why;
        const char* spec = std::getenv("GEOCOLD_TEST_DEVICE");
        context = std::make_unique<Context>(select_device(spec ? spec : "any", devices));
    }

    std::vector<DeviceInfo> devices;
    std::unique_ptr<Context> context;
};

}  // namespace gc::cl::test
