#include "host/vk/no_contraction.h"

#include <stdexcept>
#include <string>
#include <unordered_set>

namespace gc::vk {
namespace {

// Opcodes and the decoration from the SPIR-V specification (sections 3.20 and 3.42).
constexpr std::uint32_t kMagic = 0x07230203u;
constexpr std::uint32_t kHeaderWords = 5;
constexpr std::uint32_t kOpDecorate = 71;
constexpr std::uint32_t kNoContraction = 42;

bool is_float_arithmetic(std::uint32_t op)
{
    switch (op) {
    case 127:  // OpFNegate
    case 129:  // OpFAdd
    case 131:  // OpFSub
    case 133:  // OpFMul
    case 136:  // OpFDiv
    case 140:  // OpFRem
    case 141:  // OpFMod
    case 142:  // OpVectorTimesScalar
    case 143:  // OpMatrixTimesScalar
    case 144:  // OpVectorTimesMatrix
    case 145:  // OpMatrixTimesVector
    case 146:  // OpMatrixTimesMatrix
    case 148:  // OpDot
        return true;
    default:
        return false;
    }
}

// Instructions that may precede the annotations' end: the module's preamble, debug
// information and the annotations themselves. New decorations go before the first other one.
bool is_preamble_or_annotation(std::uint32_t op)
{
    switch (op) {
    case 2: case 3: case 4: case 5: case 6: case 7: case 8:  // OpSourceContinued .. OpLine
    case 10: case 11: case 14: case 15: case 16: case 17:    // OpExtension .. OpCapability
    case 71: case 72: case 73: case 74: case 75:             // OpDecorate .. OpGroupMemberDecorate
    case 317: case 330: case 331: case 332:                  // OpNoLine, OpModuleProcessed, ...
    case 5632: case 5633:                                    // OpDecorateString, OpMemberDecorateString
        return true;
    default:
        return false;
    }
}

}  // namespace

std::vector<std::uint32_t> without_contraction(std::span<const std::uint32_t> spirv)
{
    if (spirv.size() < kHeaderWords || spirv[0] != kMagic)
        throw std::invalid_argument("not a SPIR-V module (no magic number)");
    std::unordered_set<std::uint32_t> decorated;
    std::vector<std::uint32_t> results;
    std::size_t insert_at = 0;
    for (std::size_t i = kHeaderWords; i < spirv.size();) {
        const std::uint32_t words = spirv[i] >> 16;
        const std::uint32_t op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size())
            throw std::invalid_argument("SPIR-V instruction at word " + std::to_string(i) + " runs past the module");
        if (op == kOpDecorate && words >= 3 && spirv[i + 2] == kNoContraction) decorated.insert(spirv[i + 1]);
        if (is_float_arithmetic(op) && words >= 3) results.push_back(spirv[i + 2]);
        if (insert_at == 0 && !is_preamble_or_annotation(op)) insert_at = i;
        i += words;
    }
    if (insert_at == 0) insert_at = spirv.size();
    std::vector<std::uint32_t> out(spirv.begin(), spirv.begin() + static_cast<std::ptrdiff_t>(insert_at));
    for (const std::uint32_t id : results) {
        if (!decorated.insert(id).second) continue;
        out.insert(out.end(), {(3u << 16) | kOpDecorate, id, kNoContraction});
    }
    out.insert(out.end(), spirv.begin() + static_cast<std::ptrdiff_t>(insert_at), spirv.end());
    return out;
}

}  // namespace gc::vk
