// Helpers for the scene tests: scratch files, in-repo scene paths, error-message checks.
#pragma once

#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>
#include <filesystem>

#include <gtest/gtest.h>
#include <unistd.h>

#include "host/util/error.h"

namespace gc::test {

// A fresh folder per test, removed when the test ends.
class ScratchDir {
public:
    ScratchDir()
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_path = std::filesystem::temp_directory_path() /
                 ("gc_scene_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
        std::filesystem::remove_all(m_path);
        std::filesystem::create_directories(m_path);
    }
    ~ScratchDir() { std::error_code ec; std::filesystem::remove_all(m_path, ec); }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    std::filesystem::path write(const std::string& name, const std::string& content) const
    {
        const std::filesystem::path p = m_path / name;
        std::ofstream out(p, std::ios::binary);
        out << content;
        return p;
    }
    std::filesystem::path write(const std::string& name, const std::vector<unsigned char>& bytes) const
    {
        const std::filesystem::path p = m_path / name;
        std::ofstream out(p, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        return p;
    }
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
};

inline std::filesystem::path test_data_scene(const std::string& rel)
{
    return std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes" / rel;
}
inline std::filesystem::path repo_scene(const std::string& rel)
{
    return std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes" / rel;
}

inline std::vector<unsigned char> read_bytes(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs f, expects an InputError whose message contains every one of `parts`; returns the message.
inline std::string expect_input_error(const std::function<void()>& f, std::initializer_list<std::string> parts)
{
    try {
        f();
    } catch (const InputError& e) {
        const std::string msg = e.what();
        for (const std::string& part : parts) EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' not in: " << msg;
        std::printf("  error message: %s\n", msg.c_str());
        return msg;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected InputError, nothing was thrown";
    return {};
}

}  // namespace gc::test
