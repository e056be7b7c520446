#include "tools/bench/bench_output.h"

#include <cmath>
#include <cstdarg>

namespace gc::bench {

namespace {
std::FILE* g_text = stdout;
}  // namespace

void send_text_to(std::FILE* stream) { g_text = stream; }

void say(const char* format, ...)
{
    va_list args;
    va_start(args, format);
    std::vfprintf(g_text, format, args);
    va_end(args);
    std::fflush(g_text);
}

std::string ratio(double ours, double theirs)
{
    if (!(theirs > 0.0) || !(ours > 0.0)) return "n/a";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2fx", ours / theirs);
    return buffer;
}

double json_number(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace gc::bench
