// The bad-scene corpus (tests/data/bad, listed in EXPECTED.txt) through the real geocold-cl:
// every file gets its documented exit code and one clear message naming it, never a crash,
// a hang or an image; the degenerate-but-valid ones render.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "process.h"

namespace gc::test {
namespace {

const std::filesystem::path k_corpus = GC_BAD_CORPUS_DIR;

struct Case {
    std::string file;
    int exit_code = 0;
    std::string message;  // "-" = none expected (exit 0)
};

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t\r");
    const auto e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

struct Manifest {
    std::vector<Case> cases;
    std::vector<std::string> problems;  // malformed lines: reported by the Manifest test
};

// "file | exit | message" lines; '#' starts a comment line. Read while the tests register, so
// a malformed manifest shows up as a failing test, not as a crash.
const Manifest& manifest()
{
    static const Manifest m = [] {
        Manifest out;
        std::ifstream in(k_corpus / "EXPECTED.txt");
        if (!in) out.problems.push_back("cannot open " + (k_corpus / "EXPECTED.txt").string());
        std::string line;
        int number = 0;
        while (std::getline(in, line)) {
            ++number;
            if (trim(line).empty() || trim(line)[0] == '#') continue;
            const auto p1 = line.find('|');
            const auto p2 = p1 == std::string::npos ? p1 : line.find('|', p1 + 1);
            if (p2 == std::string::npos) {
                out.problems.push_back("EXPECTED.txt:" + std::to_string(number) + ": not 'file | exit | message'");
                continue;
            }
            out.cases.push_back({trim(line.substr(0, p1)), std::atoi(trim(line.substr(p1 + 1, p2 - p1 - 1)).c_str()),
                                 trim(line.substr(p2 + 1))});
        }
        return out;
    }();
    return m;
}

std::string test_name(const ::testing::TestParamInfo<Case>& info)
{
    std::string name = info.param.file;
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return name;
}

TEST(Manifest, ListsEveryScene)
{
    const std::vector<Case>& cases = manifest().cases;
    for (const std::string& p : manifest().problems) ADD_FAILURE() << p;
    ASSERT_GE(cases.size(), 40u);
    // Every scene-like file in the folder is listed, so a new file cannot be forgotten.
    for (const auto& e : std::filesystem::directory_iterator(k_corpus)) {
        const std::string name = e.path().filename().string();
        const std::string ext = e.path().extension().string();
        if (ext == ".py" || ext == ".txt" || ext == ".bin" || ext == ".mtl" || ext == ".png") continue;
        const bool listed = std::any_of(cases.begin(), cases.end(), [&](const Case& c) { return c.file == name; });
        EXPECT_TRUE(listed) << name << " is not in EXPECTED.txt";
    }
    std::printf("  %zu corpus entries\n", cases.size());
}

class BadScene : public ::testing::TestWithParam<Case> {};

TEST_P(BadScene, ClearMessageAndExitCode)
{
    const Case& c = GetParam();
    if (c.exit_code == 0 && !have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device to render " << c.file;
    const TempDir out_dir;
    const std::filesystem::path output = out_dir / "out.png";
    RunOptions options = cli_options();
    options.cwd = k_corpus;  // relative scene names, as a user types them
    options.timeout_seconds = 120;
#if !defined(__SANITIZE_ADDRESS__)
    // A file that makes the loader allocate tens of GB must fail, not swap the machine to death.
    options.max_address_space = 32ull << 30;
#endif
    const RunResult r =
        run_process(cli_path(), {c.file, "--spp", "1", "--res", "16x16", "--device", "cpu", "-o", output.string()}, options);

    std::string shown = r.err;
    while (!shown.empty() && shown.back() == '\n') shown.pop_back();
    std::printf("  %s -> %s (%.2f s)\n    %s\n", c.file.c_str(), r.describe().c_str(), r.seconds, shown.c_str());

    ASSERT_FALSE(r.timed_out) << "hang";
    ASSERT_EQ(r.signal, 0) << "crashed: " << r.describe() << "\n" << r.err;
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    if (c.message != "-") {
        EXPECT_NE(r.err.find(c.file), std::string::npos) << "the message does not name the file:\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in:\n" << r.err;
    }
    EXPECT_EQ(r.count_err_lines("internal error"), 0) << r.err;
    if (c.exit_code == 0) {
        EXPECT_EQ(r.count_err_lines("error:"), 0) << r.err;
        EXPECT_TRUE(std::filesystem::is_regular_file(output)) << "no image written";
        EXPECT_GT(std::filesystem::file_size(output), 0u);
        EXPECT_EQ(out_dir.entries(), std::vector<std::string>{"out.png"}) << "stray files beside the image";
    } else {
        EXPECT_EQ(r.count_err_lines("error:"), 1) << "want exactly one error line:\n" << r.err;
        EXPECT_TRUE(out_dir.entries().empty()) << "a failed run left files: " << out_dir.entries().front();
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadScene, ::testing::ValuesIn(manifest().cases), test_name);

}  // namespace
}  // namespace gc::test
