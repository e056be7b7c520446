#include "tools/bench/packet_probe.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "host/cl/buffer.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"
#include "tools/bench/timing.h"

namespace gc::bench {
namespace {

constexpr std::uint32_t kSeed = 12345u;

// Structure-of-arrays inputs: positions in [-1, 1]^3, unit normals, albedos in [0.5, 1].
std::array<std::vector<float>, 9> make_inputs(std::size_t count)
{
    std::array<std::vector<float>, 9> in;
    for (auto& v : in) v.resize(count);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (std::size_t i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) in[k][i] = unit(rng);
        float n[3] = {unit(rng), unit(rng), unit(rng)};
        const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) + 1e-6f;
        for (int k = 0; k < 3; ++k) in[3 + k][i] = n[k] / length;
        for (int k = 0; k < 3; ++k) in[6 + k][i] = 0.75f + 0.25f * unit(rng);
    }
    return in;
}

struct Form {
    const char* kernel_name;
    std::size_t lanes;
    std::vector<cl::Buffer<float>> outputs;
    std::vector<double> seconds;
};

}  // namespace

PacketProbeFigures run_packet_probe(const cl::Context& context, std::size_t vertices, int rounds,
                                    const cl::BuildConfig& build)
{
    const std::size_t count = (vertices + 15) / 16 * 16;
    const std::array<std::vector<float>, 9> host_inputs = make_inputs(count);
    std::vector<cl::Buffer<float>> inputs;
    for (const std::vector<float>& v : host_inputs) inputs.push_back(cl::read_only_buffer(context, v, "probe input"));

    const cl::Program program(context, "test/packet_probe.cl", "", build);
    std::array<Form, 3> forms = {Form{"packet_probe_x1", 1, {}, {}}, Form{"packet_probe_x8", 8, {}, {}},
                                 Form{"packet_probe_x16", 16, {}, {}}};
    std::array<cl::Kernel, 3> kernels;
    for (std::size_t f = 0; f < forms.size(); ++f) {
        for (int k = 0; k < 6; ++k)
            forms[f].outputs.push_back(cl::Buffer<float>::create(context, count, CL_MEM_WRITE_ONLY, "probe output"));
        kernels[f] = program.kernel(forms[f].kernel_name);
        const auto& in = inputs;
        const auto& out = forms[f].outputs;
        kernels[f].set_args(in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7], in[8], out[0], out[1], out[2],
                            out[3], out[4], out[5], kSeed, static_cast<std::uint32_t>(count));
    }
    const auto launch = [&](std::size_t f) {
        const auto start = std::chrono::steady_clock::now();
        kernels[f].launch(context, count / forms[f].lanes);
        context.finish();
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    for (std::size_t f = 0; f < forms.size(); ++f) launch(f); // first launches build PoCL's work-group functions

    PacketProbeFigures fig;
    std::vector<double> x8_ratios, x16_ratios;
    for (int r = 0; r < std::max(1, rounds); ++r) {
        for (std::size_t f = 0; f < forms.size(); ++f) forms[f].seconds.push_back(launch(f));
        x8_ratios.push_back(forms[0].seconds.back() / forms[1].seconds.back());
        x16_ratios.push_back(forms[0].seconds.back() / forms[2].seconds.back());
    }
    fig.x1_mvertices = double(count) / median(forms[0].seconds) / 1e6;
    fig.x8_mvertices = double(count) / median(forms[1].seconds) / 1e6;
    fig.x16_mvertices = double(count) / median(forms[2].seconds) / 1e6;
    fig.x8_ratio = median(x8_ratios);
    fig.x16_ratio = median(x16_ratios);

    std::vector<float> reference(count), other(count);
    for (int k = 0; k < 6; ++k) {
        forms[0].outputs[static_cast<std::size_t>(k)].read(reference);
        for (std::size_t f = 1; f < forms.size(); ++f) {
            forms[f].outputs[static_cast<std::size_t>(k)].read(other);
            for (std::size_t i = 0; i < count; ++i)
                fig.differing += std::memcmp(&reference[i], &other[i], sizeof(float)) != 0 ? 1 : 0;
        }
    }
    fig.outputs = 6 * count;
    return fig;
}

}  // namespace gc::bench
