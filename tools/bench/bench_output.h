// How geocold-bench prints: text lines go to stdout, or to stderr when stdout carries the
// JSON document (--json); and the small formatting rules that every section shares.
#pragma once

#include <cstdio>
#include <string>

namespace gc::bench {

// Where say() writes from now on (stdout until told otherwise).
void send_text_to(std::FILE* stream);

// printf to the text stream, flushed at once: a long run shows each figure as it is made.
void say(const char* format, ...) __attribute__((format(printf, 1, 2)));

// "1.23x", or "n/a" when either side is missing (zero, negative or not a number).
std::string ratio(double ours, double theirs);

// JSON has no NaN or infinity: a figure that could not be made is written as 0.
double json_number(double v);

}  // namespace gc::bench
