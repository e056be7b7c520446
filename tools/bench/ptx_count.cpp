#include "tools/bench/ptx_count.h"

#include <cctype>
#include <functional>
#include <set>
#include <vector>

namespace gc::bench {
namespace {

// The module without comments: `//` to the end of the line and `/* ... */`.
std::string strip_comments(std::string_view text)
{
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text.compare(i, 2, "//") == 0) {
            while (i < text.size() && text[i] != '\n') ++i;
            out += '\n';
        } else if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            i = end == std::string_view::npos ? text.size() : end + 1;
            out += ' ';
        } else {
            out += text[i];
        }
    }
    return out;
}

bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$' || c == '%'; }

std::string_view trim(std::string_view s)
{
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

// A statement without its leading labels (`$L__BB0_2:`) and scope braces.
std::string_view statement_body(std::string_view s)
{
    for (;;) {
        s = trim(s);
        if (!s.empty() && (s.front() == '{' || s.front() == '}')) {
            s.remove_prefix(1);
            continue;
        }
        std::size_t n = 0;
        while (n < s.size() && is_name_char(s[n])) ++n;
        if (n > 0 && n < s.size() && s[n] == ':') {
            s.remove_prefix(n + 1);
            continue;
        }
        return s;
    }
}

// The callee of a `call` statement (`call.uni (retval0), name, (params)`), or "".
std::string callee_of(std::string_view s)
{
    if (s.substr(0, 4) != "call") return {};
    s.remove_prefix(4);
    while (!s.empty() && !std::isspace(static_cast<unsigned char>(s.front())) && s.front() != '(') s.remove_prefix(1);
    s = trim(s);
    if (!s.empty() && s.front() == '(') {  // return values
        const std::size_t close = s.find(')');
        if (close == std::string_view::npos) return {};
        s = trim(s.substr(close + 1));
        if (!s.empty() && s.front() == ',') s = trim(s.substr(1));
    }
    std::size_t n = 0;
    while (n < s.size() && is_name_char(s[n])) ++n;
    return std::string(s.substr(0, n));
}

struct Function {
    int own = 0;                       // instruction statements in the body
    std::vector<std::string> callees;  // one entry per call statement
};

// The name after `.entry` or `.func` at `pos` (just past the keyword), skipping a `.func`'s
// return-value list; "" when there is none.
std::string function_name(const std::string& text, std::size_t pos)
{
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    if (pos < text.size() && text[pos] == '(') {
        const std::size_t close = text.find(')', pos);
        if (close == std::string::npos) return {};
        pos = close + 1;
        while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    }
    std::size_t end = pos;
    while (end < text.size() && is_name_char(text[end])) ++end;
    return text.substr(pos, end - pos);
}

}  // namespace

bool looks_like_ptx(std::string_view binary)
{
    return binary.find(".version") != std::string_view::npos && binary.find(".target sm_") != std::string_view::npos;
}

std::map<std::string, int> count_ptx_instructions(std::string_view ptx)
{
    const std::string text = strip_comments(ptx);
    std::map<std::string, Function> functions;
    std::size_t pos = 0;
    for (;;) {
        const std::size_t entry = text.find(".entry", pos);
        const std::size_t func = text.find(".func", pos);
        const std::size_t at = std::min(entry, func);
        if (at == std::string::npos) break;
        const std::size_t keyword_end = at + (at == entry ? 6 : 5);
        const std::string name = function_name(text, keyword_end);
        // The body opens with the first `{` after the parameter list; a `;` first means a
        // declaration (a prototype of a function defined elsewhere or not at all).
        std::size_t open = text.find_first_of("{;", keyword_end);
        if (name.empty() || open == std::string::npos || text[open] == ';') {
            pos = open == std::string::npos ? text.size() : open + 1;
            continue;
        }
        Function f;
        int depth = 0;
        std::size_t statement_start = open;
        std::size_t i = open;
        for (; i < text.size(); ++i) {
            if (text[i] == '{') ++depth;
            if (text[i] == '}' && --depth == 0) break;
            if (text[i] != ';') continue;
            const std::string_view s = statement_body(std::string_view(text).substr(statement_start, i - statement_start));
            statement_start = i + 1;
            if (s.empty() || s.front() == '.') continue;  // a directive
            ++f.own;
            if (std::string c = callee_of(s); !c.empty()) f.callees.push_back(std::move(c));
        }
        functions[name] = std::move(f);
        pos = i + 1;
    }

    std::map<std::string, int> counts;
    std::set<std::string> open_calls;  // the call chain being expanded, against recursion
    std::function<int(const std::string&)> total = [&](const std::string& name) -> int {
        const auto it = functions.find(name);
        if (it == functions.end() || open_calls.count(name)) return 0;
        open_calls.insert(name);
        int n = it->second.own;
        for (const std::string& callee : it->second.callees) n += total(callee);
        open_calls.erase(name);
        return n;
    };
    for (const auto& [name, f] : functions) counts[name] = total(name);
    return counts;
}

}  // namespace gc::bench
