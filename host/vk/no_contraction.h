// The Vulkan counterpart of `#pragma OPENCL FP_CONTRACT OFF`: every floating-point
// arithmetic result of a SPIR-V module decorated NoContraction, so the driver may not fuse a
// multiply and an add into one FMA. GLSL has no switch for that short of writing `precise`
// on every variable, and lavapipe fuses where OpenCL's kernels do not (docs/design.md,
// "Same operations everywhere").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace gc::vk {

// The module with an OpDecorate NoContraction for each result of OpFAdd, OpFSub, OpFMul,
// OpFDiv, OpFNegate, OpFRem, OpFMod, OpVectorTimesScalar, the matrix products and OpDot that
// is not decorated so already. Throws std::invalid_argument on a module that is not SPIR-V or
// whose instructions run past its end.
std::vector<std::uint32_t> without_contraction(std::span<const std::uint32_t> spirv);

}  // namespace gc::vk
