// gc_layout_list.h must name every field of every struct in gc_types.h, or the device probe
// silently checks less than it claims. This test reads gc_types.h as text and compares.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "host/cl/layout_probe.h"

namespace gc::cl {
namespace {

std::vector<std::string> entries_declared_in_gc_types()
{
    std::ifstream in(std::string(GC_TEST_SOURCE_DIR) + "/kernels/shared/gc_types.h");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text = std::regex_replace(text, std::regex(R"(/\*[\s\S]*?\*/)"), " ");
    std::vector<std::string> entries;
    const std::regex struct_re(R"(GC_STRUCT\((\w+)\)\s*\{([^}]*)\}\s*GC_STRUCT_END)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), struct_re);
         it != std::sregex_iterator(); ++it) {
        const std::string name = (*it)[1];
        const std::string body = (*it)[2];
        entries.push_back("sizeof(" + name + ")");
        // "type a, b;" declarations: the names are every identifier after the type.
        const std::regex decl_re(R"(\s*(\w+)\s+([\w\s,]+);)");
        for (auto d = std::sregex_iterator(body.begin(), body.end(), decl_re);
             d != std::sregex_iterator(); ++d) {
            const std::string names = (*d)[2];
            const std::regex name_re(R"(\w+)");
            for (auto n = std::sregex_iterator(names.begin(), names.end(), name_re);
                 n != std::sregex_iterator(); ++n) {
                entries.push_back("offsetof(" + name + ", " + n->str() + ")");
            }
        }
    }
    return entries;
}

TEST(LayoutList, NamesEveryFieldOfGcTypes)
{
    std::vector<std::string> listed;
    for (const LayoutEntry& e : host_layout()) {
        listed.push_back(e.field ? std::string("offsetof(") + e.type + ", " + e.field + ")"
                                 : std::string("sizeof(") + e.type + ")");
    }
    const std::vector<std::string> declared = entries_declared_in_gc_types();
    std::printf("gc_types.h declares %zu entries, gc_layout_list.h lists %zu\n", declared.size(),
                listed.size());
    ASSERT_GT(declared.size(), 20u) << "the gc_types.h parser found too little";
    EXPECT_EQ(listed, declared) << "update kernels/shared/gc_layout_list.h to match gc_types.h";
}

TEST(LayoutList, HostValuesAreSane)
{
    for (const LayoutEntry& e : host_layout()) {
        if (!e.field) {
            EXPECT_EQ(e.host % 16, 0u) << "sizeof(" << e.type << ")";
        } else {
            EXPECT_EQ(e.host % 4, 0u) << e.type << "." << e.field;
        }
    }
}

}  // namespace
}  // namespace gc::cl
