// geocold-imgdiff: how different are two renders? Prints the metrics of host/image/compare.h
// and, when thresholds are given, fails with exit code 6 (ExitCode::Mismatch) past them.
//   geocold-imgdiff test.exr ref.exr [--rel-mse-max X] [--rmse-max X] [--max-abs-max X]
//                   [--tol REL] [--within-min F] [--mean-rel-max X] [--heatmap out.png [--heatmap-scale S]]
//                   [--variance ref_var.exr --spp N [--alpha A] [--z-pass-min F]]
// Exit codes: 0 within thresholds, 2 bad usage, 3 unreadable/mismatched input, 5 heat map not
// written, 6 a threshold exceeded (non-finite pixels count as exceeding any threshold).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "host/image/compare.h"
#include "host/image/image_io.h"
#include "host/util/error.h"

namespace {

constexpr const char* k_usage =
    "usage: geocold-imgdiff TEST REF [options]\n"
    "  --rel-mse-max X     fail (exit 6) when mean((t-r)^2/(r^2+1e-2)) > X\n"
    "  --rmse-max X        fail when the RMSE > X\n"
    "  --max-abs-max X     fail when the largest |t-r| > X\n"
    "  --tol REL           relative tolerance for the 'within' fraction (default 0.01; +1e-3 absolute)\n"
    "  --within-min F      fail when fewer than F of the pixels are within tolerance\n"
    "  --mean-rel-max X    fail when a channel's image mean differs from REF's by more than X of it\n"
    "  --heatmap PATH      write a difference heat map (black < red < yellow < white)\n"
    "  --heatmap-scale S   heat map value of 1 at |diff| = 1/S (default: the largest difference)\n"
    "  --variance PATH     per-sample variance of REF: run the per-pixel Z-test of TEST against REF\n"
    "  --spp N             samples per pixel of TEST (needed with --variance)\n"
    "  --alpha A           Z-test significance before Sidak correction (default 0.01)\n"
    "  --z-pass-min F      fail when fewer than F of the pixels pass the Z-test (default 0.9975)\n"
    "exit codes: 0 ok, 2 usage, 3 unreadable input, 5 heat map not written, 6 threshold exceeded\n";

struct Options {
    std::string test, ref, heatmap, variance;
    std::optional<double> rel_mse_max, rmse_max, max_abs_max, within_min, mean_rel_max;
    gc::PixelTolerance tol;  // the reference rule: --tol sets its relative part
    double alpha = 0.01, z_pass_min = 0.9975;
    float heatmap_scale = 0;
    uint32_t spp = 0;
};

double parse_number(const std::string& flag, const char* text)
{
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0') throw gc::UsageError(flag + " needs a number, got '" + text + "'");
    return v;
}

Options parse(int argc, char** argv)
{
    Options o;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            std::fputs(k_usage, stdout);
            std::exit(0);
        }
        if (a.rfind("--", 0) != 0) {
            positional.push_back(a);
            continue;
        }
        if (i + 1 >= argc) throw gc::UsageError(a + " needs a value");
        const char* v = argv[++i];
        if (a == "--rel-mse-max") o.rel_mse_max = parse_number(a, v);
        else if (a == "--rmse-max") o.rmse_max = parse_number(a, v);
        else if (a == "--max-abs-max") o.max_abs_max = parse_number(a, v);
        else if (a == "--within-min") o.within_min = parse_number(a, v);
        else if (a == "--mean-rel-max") o.mean_rel_max = parse_number(a, v);
        else if (a == "--tol") o.tol.rel = parse_number(a, v);
        else if (a == "--heatmap") o.heatmap = v;
        else if (a == "--heatmap-scale") o.heatmap_scale = float(parse_number(a, v));
        else if (a == "--variance") o.variance = v;
        else if (a == "--spp") o.spp = uint32_t(parse_number(a, v));
        else if (a == "--alpha") o.alpha = parse_number(a, v);
        else if (a == "--z-pass-min") o.z_pass_min = parse_number(a, v);
        else throw gc::UsageError("unknown option '" + a + "'");
    }
    if (positional.size() != 2) throw gc::UsageError("expected two images (TEST REF), got " + std::to_string(positional.size()));
    if (!o.variance.empty() && o.spp == 0) throw gc::UsageError("--variance needs --spp N (N > 0)");
    o.test = positional[0];
    o.ref = positional[1];
    return o;
}

// Prints one threshold check and returns whether it failed.
bool exceeds(const char* name, double value, std::optional<double> limit, bool upper)
{
    if (!limit) return false;
    const bool bad = upper ? !(value <= *limit) : !(value >= *limit);
    std::printf("  %-18s %.6g %s %.6g  %s\n", name, value, upper ? "<=" : ">=", *limit, bad ? "FAIL" : "ok");
    return bad;
}

int run(int argc, char** argv)
{
    const Options o = parse(argc, argv);
    const gc::Film test = gc::read_image(o.test);
    const gc::Film ref = gc::read_image(o.ref);
    const gc::ImageDifference d = gc::compare_images(test, ref, o.tol);

    std::printf("%s vs %s (%ux%u)\n", o.test.c_str(), o.ref.c_str(), test.width(), test.height());
    std::printf("  rmse               %.6g\n", d.rmse);
    std::printf("  rel_mse            %.6g\n", d.rel_mse);
    std::printf("  max_abs            %.6g\n", d.max_abs);
    std::printf("  within_tolerance   %.6f  (|t-r| <= %g*|r| + 1e-3)\n", d.within_tolerance, o.tol.rel);
    std::printf("  nonfinite_pixels   %zu\n", d.nonfinite);
    std::printf("  mean_rel_diff      %.6g  (largest over RGB of |mean(t) - mean(r)| / mean(r))\n", d.mean_rel_diff);

    bool failed = false;
    std::optional<gc::ZTestResult> z;
    if (!o.variance.empty()) {
        const gc::Film var = gc::read_image(o.variance);
        z = gc::z_test(test, o.spp, ref, var, o.alpha);
        std::printf("  z_test             %zu/%zu pixels pass (%.4f), alpha_sidak %.3g, min p %.3g, max z %.3g\n",
                    z->passed, z->tested, z->pass_fraction, z->alpha_sidak, z->min_p_value, z->max_z);
        failed |= exceeds("z_pass_fraction", z->pass_fraction, o.z_pass_min, false);
    }
    failed |= exceeds("rel_mse", d.rel_mse, o.rel_mse_max, true);
    failed |= exceeds("rmse", d.rmse, o.rmse_max, true);
    failed |= exceeds("max_abs", d.max_abs, o.max_abs_max, true);
    failed |= exceeds("within_tolerance", d.within_tolerance, o.within_min, false);
    failed |= exceeds("mean_rel_diff", d.mean_rel_diff, o.mean_rel_max, true);
    const bool any_threshold = o.rel_mse_max || o.rmse_max || o.max_abs_max || o.within_min || o.mean_rel_max || z;
    if (any_threshold && d.nonfinite > 0) {
        std::printf("  nonfinite pixels present: FAIL\n");
        failed = true;
    }

    if (!o.heatmap.empty()) {
        gc::write_image(o.heatmap, gc::difference_heatmap(test, ref, o.heatmap_scale), gc::ImageMetadata{});
        std::printf("  heat map written to %s\n", o.heatmap.c_str());
    }
    std::printf("%s\n", failed ? "MISMATCH" : "OK");
    return failed ? int(gc::ExitCode::Mismatch) : 0;
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        return run(argc, argv);
    } catch (const gc::UsageError& e) {
        std::fprintf(stderr, "geocold-imgdiff: %s\n%s", e.what(), k_usage);
        return int(gc::ExitCode::Usage);
    } catch (const gc::Error& e) {
        std::fprintf(stderr, "geocold-imgdiff: %s\n", e.what());
        return int(e.code());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geocold-imgdiff: internal error: %s\n", e.what());
        return int(gc::ExitCode::Internal);
    }
}
