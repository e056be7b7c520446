#include "host/app/consistency_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "host/util/error.h"

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

ConsistencyPair compare_renders(const Film& a, const Film& b, const ConsistencyTolerances& tol)
{
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError("consistency: renders differ in size (" + std::to_string(a.width()) + "x" +
                         std::to_string(a.height()) + " vs " + std::to_string(b.width()) + "x" +
                         std::to_string(b.height()) + ")");
    if (a.empty()) throw InputError("consistency: the renders are empty");

    ConsistencyPair p;
    p.pixels = a.pixel_count();
    double rel = 0.0, sum_a = 0.0, sum_b = 0.0;
    std::size_t within = 0, finite = 0;
    for (std::size_t i = 0; i < p.pixels; ++i) {
        const float* pa = a.data().data() + i * 4;
        const float* pb = b.data().data() + i * 4;
        bool ok = true;
        bool is_finite = true;
        for (int c = 0; c < 3; ++c) is_finite = is_finite && std::isfinite(pa[c]) && std::isfinite(pb[c]);
        if (!is_finite) {
            ++p.nonfinite;
            continue;
        }
        ++finite;
        p.identical += std::memcmp(pa, pb, 3 * sizeof(float)) == 0;
        for (int c = 0; c < 3; ++c) {
            const double va = pa[c];
            const double vb = pb[c];
            const double diff = std::fabs(vb - va);
            rel += diff * diff / (va * va + 1e-2);
            p.max_abs = std::max(p.max_abs, diff);
            ok = ok && (diff <= tol.pixel_rel_tol * std::max(std::fabs(va), std::fabs(vb)) || diff <= tol.pixel_abs_tol);
            sum_a += va;
            sum_b += vb;
        }
        within += ok;
    }
    // Non-finite pixels count as outside the tolerance: divide by all pixels.
    p.within = double(within) / double(p.pixels);
    if (finite > 0) {
        p.rel_mse = rel / (3.0 * double(finite));
        p.mean_a = sum_a / (3.0 * double(finite));
        p.mean_b = sum_b / (3.0 * double(finite));
    }

    if (p.nonfinite > 0) p.why = std::to_string(p.nonfinite) + " pixels with NaN/Inf";
    else if (p.mean_a == 0.0 && p.mean_b == 0.0) p.why = "both images are black (the comparison proves nothing)";
    else if (!(p.rel_mse <= tol.max_rel_mse)) p.why = "rel MSE " + format("%.3g", p.rel_mse) + " > " + format("%.3g", tol.max_rel_mse);
    else if (!(p.within >= tol.min_within))
        p.why = "only " + percent(p.within) + " of pixels within tolerance (< " + percent(tol.min_within) + ")";
    p.passed = p.why.empty();
    return p;
}

std::vector<ConsistencyPair> compare_all(const std::vector<ConsistencyRender>& renders, const ConsistencyTolerances& tol)
{
    std::vector<ConsistencyPair> pairs;
    for (std::size_t i = 0; i < renders.size(); ++i) {
        for (std::size_t j = i + 1; j < renders.size(); ++j) {
            ConsistencyPair p = compare_renders(renders[i].image, renders[j].image, tol);
            p.a = i;
            p.b = j;
            pairs.push_back(std::move(p));
        }
    }
    return pairs;
}

bool ConsistencyRun::passed() const
{
    return std::all_of(pairs.begin(), pairs.end(), [](const ConsistencyPair& p) { return p.passed; });
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
        std::snprintf(line, sizeof line, "  %-8s  %-10.3e  %-10.3e  %-12s  %-10s  %s\n", pair_name(p).c_str(), p.rel_mse,
                      p.max_abs, percent(p.within).c_str(), percent(double(p.identical) / double(p.pixels)).c_str(),
                      p.passed ? "pass" : ("FAIL: " + p.why).c_str());
        s << line;
    }
    const ConsistencyTolerances& t = run.tolerances;
    s << "  limits: rel MSE <= " << format("%.3g", t.max_rel_mse) << "; >= " << percent(t.min_within)
      << " of pixels within tolerance, where a pixel is within when every channel has |b - a| <= "
      << format("%.3g", t.pixel_rel_tol) << " * max(|a|, |b|) or |b - a| <= " << format("%.3g", t.pixel_abs_tol) << "\n";
    const std::size_t failed = static_cast<std::size_t>(
        std::count_if(run.pairs.begin(), run.pairs.end(), [](const ConsistencyPair& p) { return !p.passed; }));
    if (failed == 0) s << "consistency: PASSED (" << run.pairs.size() << " pair" << (run.pairs.size() == 1 ? "" : "s") << ")\n";
    else s << "consistency: FAILED (" << failed << " of " << run.pairs.size() << " pairs)\n";
    return s.str();
}

std::string format_json(const ConsistencyRun& run)
{
    std::ostringstream s;
    const ConsistencyTolerances& t = run.tolerances;
    s << "{\n";
    s << "  \"scene\": " << json_string(run.scene) << ",\n";
    s << "  \"integrator\": " << json_string(run.integrator) << ",\n";
    s << "  \"width\": " << run.width << ", \"height\": " << run.height << ", \"spp\": " << run.spp
      << ", \"seed\": " << run.seed << ",\n";
    s << "  \"tolerances\": {\"max_rel_mse\": " << json_number(t.max_rel_mse)
      << ", \"min_within\": " << json_number(t.min_within) << ", \"pixel_rel_tol\": " << json_number(t.pixel_rel_tol)
      << ", \"pixel_abs_tol\": " << json_number(t.pixel_abs_tol) << "},\n";
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
        s << (i ? ",\n" : "\n") << "    {\"a\": " << p.a << ", \"b\": " << p.b << ", \"rel_mse\": " << json_number(p.rel_mse)
          << ", \"max_abs\": " << json_number(p.max_abs) << ", \"within\": " << json_number(p.within)
          << ", \"identical\": " << json_number(double(p.identical) / double(std::max<std::size_t>(p.pixels, 1)))
          << ", \"pixels\": " << p.pixels << ", \"nonfinite\": " << p.nonfinite
          << ", \"mean_a\": " << json_number(p.mean_a) << ", \"mean_b\": " << json_number(p.mean_b)
          << ", \"passed\": " << (p.passed ? "true" : "false") << ", \"why\": " << json_string(p.why) << "}";
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
