// The "same operations everywhere" rule for the code OpenCL's compiler never sees: the GLSL of
// the Vulkan reference (kernels/vk/*.comp, *.glsl). The OpenCL programs are checked by the
// compiler itself (forbidden_builtins.h, force-included by the KernelBuiltinRule tests); the
// list of forbidden names is read from that header, so it is written in one place.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kSource = GC_TEST_SOURCE_DIR;

std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every name after "#pragma clang poison" in the header.
std::set<std::string> forbidden_names()
{
    std::set<std::string> names;
    std::istringstream lines(read_text(kSource / "tests/kernels/forbidden_builtins.h"));
    const std::string pragma = "#pragma clang poison";
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind(pragma, 0) != 0) continue;
        std::istringstream words(line.substr(pragma.size()));
        for (std::string w; words >> w;) names.insert(w);
    }
    return names;
}

// The source with comments blanked out (line breaks kept, so line numbers stay right).
std::string without_comments(const std::string& text)
{
    std::string out = text;
    for (std::size_t i = 0; i + 1 < out.size(); ++i) {
        if (out[i] == '/' && out[i + 1] == '/') {
            while (i < out.size() && out[i] != '\n') out[i++] = ' ';
        } else if (out[i] == '/' && out[i + 1] == '*') {
            for (; i + 1 < out.size() && !(out[i] == '*' && out[i + 1] == '/'); ++i)
                if (out[i] != '\n') out[i] = ' ';
            if (i + 1 < out.size()) out[i] = out[i + 1] = ' ';
        }
    }
    return out;
}

struct Use {
    std::string name;
    int line;
};

// Identifiers from `names` used as a call (name followed by '('), not as a member (x.length()).
std::vector<Use> forbidden_calls(const std::string& code, const std::set<std::string>& names)
{
    std::vector<Use> uses;
    int line = 1;
    for (std::size_t i = 0; i < code.size();) {
        const char c = code[i];
        if (c == '\n') ++line;
        if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_')) {
            ++i;
            continue;
        }
        std::size_t end = i;
        while (end < code.size() && (std::isalnum(static_cast<unsigned char>(code[end])) || code[end] == '_')) ++end;
        const std::string word = code.substr(i, end - i);
        std::size_t next = end;
        while (next < code.size() && (code[next] == ' ' || code[next] == '\t')) ++next;
        const bool member = i > 0 && code[i - 1] == '.';
        if (!member && next < code.size() && code[next] == '(' && names.count(word)) uses.push_back({word, line});
        i = end;
    }
    return uses;
}

TEST(BuiltinRule, TheListIsRead)
{
    const std::set<std::string> names = forbidden_names();
    std::printf("forbidden built-ins: %zu names\n", names.size());
    for (const char* expected : {"dot", "normalize", "length", "cross", "pow", "atan2", "native_sqrt", "fma"})
        EXPECT_TRUE(names.count(expected)) << expected;
}

TEST(BuiltinRule, ScannerFindsCallsOutsideComments)
{
    const std::set<std::string> names = {"dot", "length"};
    const std::string code = without_comments("// dot(a, b)\n/* length(x) */ float y = dot (a, b);\nint n = v.length();\n");
    const std::vector<Use> uses = forbidden_calls(code, names);
    ASSERT_EQ(uses.size(), 1u);
    EXPECT_EQ(uses[0].name, "dot");
    EXPECT_EQ(uses[0].line, 2);
}

// The raster preview (raster.vert/.frag) is exempt: which pixels a rasteriser covers is the
// driver's choice anyway, and the cross-check excludes edge pixels for that reason.
TEST(BuiltinRule, VulkanComputeShadersUseTheSharedHelpers)
{
    const std::set<std::string> names = forbidden_names();
    std::size_t files = 0;
    std::ostringstream found;
    for (const auto& entry : fs::directory_iterator(kSource / "kernels/vk")) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".comp" && ext != ".glsl") continue;
        ++files;
        for (const Use& u : forbidden_calls(without_comments(read_text(entry.path())), names))
            found << entry.path().filename().string() << ":" << u.line << ": " << u.name << "\n";
    }
    std::printf("GLSL compute sources scanned: %zu\n", files);
    EXPECT_GE(files, 3u);
    EXPECT_EQ(found.str(), "") << "built-ins whose precision the driver chooses:\n" << found.str();
}

}  // namespace
