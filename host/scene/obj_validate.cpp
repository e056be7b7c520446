#include "host/scene/obj_validate.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

#include "host/util/error.h"

namespace gc {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

// Whitespace-separated tokens of one line, stopping at a comment.
std::vector<std::string_view> tokenize(std::string_view line)
{
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        if (i >= line.size() || line[i] == '#') break;
        std::size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        tokens.push_back(line.substr(i, j - i));
        i = j;
    }
    return tokens;
}

class LineError {
public:
    LineError(const std::string& file, std::size_t line) : m_file(file), m_line(line) {}
    [[noreturn]] void fail(const std::string& what) const
    {
        throw InputError(m_file + ":" + std::to_string(m_line) + ": " + what);
    }

private:
    const std::string& m_file;
    std::size_t m_line;
};

// The value as tinyobjloader will store it (a float), rejecting what it would silently turn into 0.
void check_number(std::string_view token, const LineError& at, const char* what)
{
    std::string_view s = token;
    if (s.size() > 1 && s[0] == '+') s.remove_prefix(1);  // from_chars does not take '+'
    double value = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec == std::errc::result_out_of_range)
        at.fail(std::string(what) + " '" + std::string(token) + "' is out of range");
    if (ec != std::errc() || end != s.data() + s.size())
        at.fail(std::string(what) + " '" + std::string(token) + "' is not a number");
    if (!std::isfinite(value) || !std::isfinite(static_cast<float>(value)))
        at.fail(std::string(what) + " '" + std::string(token) + "' is not finite");
}

void check_numbers(const std::vector<std::string_view>& tokens, std::size_t required, std::size_t allowed,
                   const LineError& at, const char* what)
{
    const std::size_t given = tokens.size() - 1;
    if (given < required)
        at.fail(std::string(what) + " needs " + std::to_string(required) + " values, got " + std::to_string(given));
    // Trailing extras beyond what the format allows (e.g. vertex colours) are left to tinyobjloader.
    const std::size_t check = given < allowed ? given : allowed;
    for (std::size_t k = 1; k <= check; ++k) check_number(tokens[k], at, what);
}

std::string plural(const std::string& kind, std::size_t n)
{
    if (n == 1) return kind;
    return kind == "vertex" ? "vertices" : kind + "s";
}

// One index of a face corner: 1-based, or negative counting back from the newest element.
void check_index(std::string_view part, std::size_t declared, const LineError& at, const char* kind)
{
    long long index = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
    if (ec != std::errc() || end != part.data() + part.size())
        at.fail(std::string(kind) + " index '" + std::string(part) + "' is not an integer");
    if (index == 0) at.fail(std::string(kind) + " index 0 is invalid (indices start at 1)");
    const long long n = static_cast<long long>(declared);
    if (index > n || -index > n)
        at.fail(std::string(kind) + " index " + std::to_string(index) + " out of range (" + std::to_string(declared) +
                " " + plural(kind, declared) + " declared so far)");
}

void check_face(const std::vector<std::string_view>& tokens, const ObjScan& scan, const LineError& at)
{
    const std::size_t corners = tokens.size() - 1;
    if (corners < 3) at.fail("face needs at least 3 vertices, got " + std::to_string(corners));
    for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view corner = tokens[k];
        const std::size_t s1 = corner.find('/');
        const std::string_view v = corner.substr(0, s1);
        check_index(v, scan.positions, at, "vertex");
        if (s1 == std::string_view::npos) continue;
        const std::string_view rest = corner.substr(s1 + 1);
        const std::size_t s2 = rest.find('/');
        const std::string_view vt = rest.substr(0, s2);
        if (!vt.empty()) check_index(vt, scan.texcoords, at, "texture coordinate");
        if (s2 == std::string_view::npos) continue;
        const std::string_view vn = rest.substr(s2 + 1);
        if (!vn.empty()) check_index(vn, scan.normals, at, "normal");
    }
}

// Calls visit(tokens, at) for each non-empty line. Lines end at \n, \r\n or a lone \r, as
// tinyobjloader splits them.
template <typename Visit>
void for_each_line(std::string_view text, const std::string& file_name, const char* kind, Visit visit)
{
    if (text.find('\0') != std::string_view::npos)
        throw InputError(file_name + ": contains binary data (NUL bytes); not a text " + kind + " file");
    std::size_t line_number = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find_first_of("\r\n", pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(pos, end - pos);
        pos = end;
        if (pos < text.size()) {
            if (text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ++pos;
            ++pos;
        }
        ++line_number;
        const std::vector<std::string_view> tokens = tokenize(line);
        if (!tokens.empty()) visit(tokens, LineError(file_name, line_number));
    }
}

}  // namespace

ObjScan validate_obj_text(std::string_view text, const std::string& file_name)
{
    ObjScan scan;
    for_each_line(text, file_name, ".obj", [&](const std::vector<std::string_view>& tokens, const LineError& at) {
        const std::string_view key = tokens[0];
        if (key == "v") {
            check_numbers(tokens, 3, 3, at, "vertex coordinate");
            ++scan.positions;
        } else if (key == "vt") {
            check_numbers(tokens, 1, 2, at, "texture coordinate");
            ++scan.texcoords;
        } else if (key == "vn") {
            check_numbers(tokens, 3, 3, at, "normal component");
            ++scan.normals;
        } else if (key == "f") {
            check_face(tokens, scan, at);
            ++scan.faces;
            scan.triangles += tokens.size() - 3;
        } else if (key == "mtllib") {
            for (std::size_t k = 1; k < tokens.size(); ++k) scan.material_libraries.emplace_back(tokens[k]);
        }
    });
    return scan;
}

void validate_mtl_text(std::string_view text, const std::string& file_name)
{
    for_each_line(text, file_name, ".mtl", [](const std::vector<std::string_view>& tokens, const LineError& at) {
        const std::string_view key = tokens[0];
        const std::string what = std::string(key) + " value";
        if (key == "Ka" || key == "Kd" || key == "Ks" || key == "Ke" || key == "Tf") {
            // "Kd spectral file.rfl" and "Kd xyz x y z" are other colour forms tinyobjloader ignores.
            if (tokens.size() > 1 && (tokens[1] == "spectral" || tokens[1] == "xyz")) return;
            check_numbers(tokens, 1, 3, at, what.c_str());
        } else if (key == "Ns" || key == "Ni" || key == "d" || key == "Tr") {
            check_numbers(tokens, 1, 1, at, what.c_str());
        }
    });
}

}  // namespace gc
