#include "host/app/consistency_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace gc {
namespace {

std::string format(const char* fmt, double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, fmt, value);
    return buffer;
}

std::string percent(double fraction) { return format("%.3f %%", 100.0 * fraction); }

// JSON string literal (RFC 8259): quotes, backslashes and control characters escaped.
std::string json_string(const std::string& s)
{
    std::string out = "\"";
    for (const char ch : s) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '"') out += "\\\"";
        else if (c == '\\') out += "\\\\";
        else if (c == '\n') out += "\\n";
        else if (c < 0x20) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
            out += buffer;
        } else out += ch;
    }
    return out + "\"";
}

// Shortest text that reads back as the same double; JSON has no NaN/Inf, so those are null.
std::string json_number(double v)
{
    if (!std::isfinite(v)) return "null";
    return format("%.17g", v);
}

std::string pair_name(const ConsistencyPair& p) { return std::to_string(p.a) + " vs " + std::to_string(p.b); }

}  // namespace

std::vector<ConsistencyPair> compare_all(const std::vector<ConsistencyRender>& renders, const AgreementLimits& limits)
{
    std::vector<ConsistencyPair> pairs;
    for (std::size_t i = 0; i < renders.size(); ++i) {
        for (std::size_t j = i + 1; j < renders.size(); ++j) {
            ConsistencyPair p;
            p.a = i;
            p.b = j;
            p.diff = compare_images(renders[j].image, renders[i].image, limits.pixel);
            p.verdict = judge_agreement(p.diff, limits);
            pairs.push_back(std::move(p));
        }
    }
    return pairs;
}

bool ConsistencyRun::passed() const
{
    return std::all_of(pairs.begin(), pairs.end(), [](const ConsistencyPair& p) { return p.verdict.passed(); });
}

std::string format_report(const ConsistencyRun& run)
{
    std::ostringstream s;
    s << "consistency: " << run.scene << ", " << run.integrator << ", " << run.width << "x" << run.height << ", "
      << run.spp << " spp, seed " << run.seed << "\n";
    for (std::size_t i = 0; i < run.renders.size(); ++i) {
        const ConsistencyRender& r = run.renders[i];
        s << "  [" << i << "] " << r.api << "  " << r.device;
        if (!r.platform.empty()) s << " (" << r.platform << ")";
        s << "  " << format("%.2f s", r.seconds) << "\n";
    }
    for (const std::string& note : run.notes) s << "  note: " << note << "\n";
    if (run.skipped()) {
        s << "consistency: SKIPPED: " << run.renders.size()
          << " device(s) rendered, at least two are needed for a comparison\n";
        return s.str();
    }
    char line[256];
    std::snprintf(line, sizeof line, "  %-8s  %-10s  %-10s  %-12s  %-10s  %s\n", "pair", "rel MSE", "max |diff|",
                  "within tol", "identical", "result");
    s << line;
    for (const ConsistencyPair& p : run.pairs) {
        std::snprintf(line, sizeof line, "  %-8s  %-10.3e  %-10.3e  %-12s  %-10s  %s\n", pair_name(p).c_str(),
                      p.diff.rel_mse, p.diff.max_abs, percent(p.diff.within_tolerance).c_str(),
                      percent(p.diff.identical).c_str(), p.verdict.passed() ? "pass" : ("FAIL: " + p.verdict.why).c_str());
        s << line;
    }
    const AgreementLimits& t = run.tolerances;
    s << "  limits: rel MSE <= " << format("%.3g", t.max_rel_mse) << "; >= " << percent(t.min_within)
      << " of pixels within tolerance, where a pixel is within when every channel has |b - a| <= "
      << format("%.3g", t.pixel.rel) << " * max(|a|, |b|) or |b - a| <= " << format("%.3g", t.pixel.abs) << "\n";
    const std::size_t failed = static_cast<std::size_t>(
        std::count_if(run.pairs.begin(), run.pairs.end(), [](const ConsistencyPair& p) { return !p.verdict.passed(); }));
    if (failed == 0) s << "consistency: PASSED (" << run.pairs.size() << " pair" << (run.pairs.size() == 1 ? "" : "s") << ")\n";
    else s << "consistency: FAILED (" << failed << " of " << run.pairs.size() << " pairs)\n";
    return s.str();
}

std::string format_json(const ConsistencyRun& run)
{
    std::ostringstream s;
    const AgreementLimits& t = run.tolerances;
    s << "{\n";
    s << "  \"scene\": " << json_string(run.scene) << ",\n";
    s << "  \"integrator\": " << json_string(run.integrator) << ",\n";
    s << "  \"width\": " << run.width << ", \"height\": " << run.height << ", \"spp\": " << run.spp
      << ", \"seed\": " << run.seed << ",\n";
    s << "  \"tolerances\": {\"max_rel_mse\": " << json_number(t.max_rel_mse)
      << ", \"min_within\": " << json_number(t.min_within) << ", \"pixel_rel_tol\": " << json_number(t.pixel.rel)
      << ", \"pixel_abs_tol\": " << json_number(t.pixel.abs) << "},\n";
    s << "  \"devices\": [";
    for (std::size_t i = 0; i < run.renders.size(); ++i) {
        const ConsistencyRender& r = run.renders[i];
        s << (i ? ",\n" : "\n") << "    {\"index\": " << i << ", \"api\": " << json_string(r.api)
          << ", \"device\": " << json_string(r.device) << ", \"platform\": " << json_string(r.platform)
          << ", \"seconds\": " << json_number(r.seconds) << "}";
    }
    s << (run.renders.empty() ? "" : "\n  ") << "],\n";
    s << "  \"pairs\": [";
    for (std::size_t i = 0; i < run.pairs.size(); ++i) {
        const ConsistencyPair& p = run.pairs[i];
        const ImageDifference& d = p.diff;
        s << (i ? ",\n" : "\n") << "    {\"a\": " << p.a << ", \"b\": " << p.b << ", \"rel_mse\": " << json_number(d.rel_mse)
          << ", \"max_abs\": " << json_number(d.max_abs) << ", \"within\": " << json_number(d.within_tolerance)
          << ", \"identical\": " << json_number(d.identical) << ", \"pixels\": " << d.pixels + d.nonfinite
          << ", \"nonfinite\": " << d.nonfinite << ", \"mean_a\": " << json_number(d.mean_ref)
          << ", \"mean_b\": " << json_number(d.mean_test) << ", \"passed\": " << (p.verdict.passed() ? "true" : "false")
          << ", \"why\": " << json_string(p.verdict.why) << "}";
    }
    s << (run.pairs.empty() ? "" : "\n  ") << "],\n";
    s << "  \"notes\": [";
    for (std::size_t i = 0; i < run.notes.size(); ++i) s << (i ? ", " : "") << json_string(run.notes[i]);
    s << "],\n";
    s << "  \"skipped\": " << (run.skipped() ? "true" : "false") << ",\n";
    s << "  \"passed\": " << (run.passed() ? "true" : "false") << "\n";
    s << "}\n";
    return s.str();
}

std::string heatmap_stem(const ConsistencyRun& run, const ConsistencyPair& pair)
{
    std::string stem = std::filesystem::path(run.scene).stem().string();
    if (stem.empty()) stem = "scene";
    return stem + "_" + std::to_string(pair.a) + "-vs-" + std::to_string(pair.b);
}

}  // namespace gc
