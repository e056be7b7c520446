#include "host/scene/gltf_accessor.h"

#include <tiny_gltf.h>

#include "host/util/error.h"

namespace gc {

static_assert(kGltfByte == TINYGLTF_COMPONENT_TYPE_BYTE && kGltfUnsignedByte == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
              kGltfShort == TINYGLTF_COMPONENT_TYPE_SHORT &&
              kGltfUnsignedShort == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
              kGltfUnsignedInt == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && kGltfFloat == TINYGLTF_COMPONENT_TYPE_FLOAT);

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& what) { throw InputError(file + ": " + what); }

std::string type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "type " + std::to_string(type);
    }
}

std::string component_name(int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "component type " + std::to_string(ct);
    }
}

}  // namespace

AccessorView gltf_accessor_view(const tinygltf::Model& model, int index, AccessorUse use, const std::string& file,
                                const std::string& where)
{
    const std::string ctx = where + ", accessor " + std::to_string(index) + ": ";
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
        fail(file, where + ": accessor index " + std::to_string(index) + " out of range (" +
             std::to_string(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    if (a.sparse.isSparse) fail(file, ctx + "sparse accessors are not supported");

    const int ct = a.componentType;
    // Core glTF 2.0 plus KHR_mesh_quantization, which adds integer vertex attributes:
    // POSITION any of (unsigned) byte/short, normalized or not; NORMAL and TANGENT
    // normalized byte/short; TEXCOORD (unsigned) byte/short, normalized or not. Normalized
    // values read back by the spec's formulas (AccessorView::get). Accepted whether or not the
    // file declares the extension: reading them is unambiguous.
    const bool is_float = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool is_small_int = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                              ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool is_signed_normalized =
        a.normalized && (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT);
    bool ok_type = false;
    switch (use) {
    case AccessorUse::Position: ok_type = a.type == TINYGLTF_TYPE_VEC3 && (is_float || is_small_int); break;
    case AccessorUse::Normal: ok_type = a.type == TINYGLTF_TYPE_VEC3 && (is_float || is_signed_normalized); break;
    case AccessorUse::TexCoord: ok_type = a.type == TINYGLTF_TYPE_VEC2 && (is_float || is_small_int); break;
    case AccessorUse::Index:
        ok_type = a.type == TINYGLTF_TYPE_SCALAR &&
                  (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                   ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
        break;
    case AccessorUse::Tangent: ok_type = a.type == TINYGLTF_TYPE_VEC4 && (is_float || is_signed_normalized); break;
    }
    // A normalized FLOAT or a normalized index is not glTF.
    if (a.normalized && (is_float || use == AccessorUse::Index)) ok_type = false;
    if (!ok_type) {
        static const char* expected[] = {
            "VEC3 FLOAT or (KHR_mesh_quantization) BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT",
            "VEC3 FLOAT or (KHR_mesh_quantization) normalized BYTE/SHORT",
            "VEC2 FLOAT, normalized UNSIGNED_BYTE/SHORT or (KHR_mesh_quantization) BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT",
            "SCALAR UNSIGNED_BYTE/SHORT/INT",
            "VEC4 FLOAT or (KHR_mesh_quantization) normalized BYTE/SHORT"};
        fail(file, ctx + type_name(a.type) + " " + component_name(ct) + (a.normalized ? " (normalized)" : "") +
             " where " + expected[static_cast<int>(use)] + " is required");
    }

    AccessorView v;
    v.count = a.count;
    v.component_type = ct;
    v.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    v.normalized = a.normalized;
    const std::size_t element = static_cast<std::size_t>(v.components) *
                                static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(ct)));
    if (a.bufferView < 0) {
        // The spec allows an accessor with no bufferView: all zeros. Its count is not bounded
        // by any bytes in the file, so a hostile count would make us allocate without limit
        // (found by fuzz_gltf): accept only what a real mesh could need.
        if (a.count > k_max_zero_elements)
            fail(file, ctx + "has no bufferView (all zeros) but claims " + std::to_string(a.count) +
                 " elements; more than " + std::to_string(k_max_zero_elements) + " is refused");
        return v;
    }
    if (static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
        fail(file, ctx + "bufferView " + std::to_string(a.bufferView) + " out of range (" +
             std::to_string(model.bufferViews.size()) + " bufferViews)");
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
        fail(file, ctx + "bufferView " + std::to_string(a.bufferView) + " names buffer " + std::to_string(bv.buffer) +
             ", out of range (" + std::to_string(model.buffers.size()) + " buffers)");
    const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(bv.buffer)];
    if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
        fail(file, ctx + "bufferView " + std::to_string(a.bufferView) + " (bytes " + std::to_string(bv.byteOffset) + " + " +
             std::to_string(bv.byteLength) + ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" +
             std::to_string(buffer.data.size()) + " bytes)");
    v.stride = bv.byteStride ? bv.byteStride : element;
    if (v.stride < element)
        fail(file, ctx + "byteStride " + std::to_string(v.stride) + " is smaller than an element (" + std::to_string(element) + " bytes)");
    if (v.count > 0) {
        // count <= byteLength first, so the product below cannot overflow.
        if (v.count > bv.byteLength || a.byteOffset > bv.byteLength ||
            v.stride * (v.count - 1) + element > bv.byteLength - a.byteOffset)
            fail(file, ctx + std::to_string(v.count) + " elements of " + std::to_string(element) + " bytes (stride " +
                 std::to_string(v.stride) + ") from byte " + std::to_string(a.byteOffset) +
                 " run past the end of bufferView " + std::to_string(a.bufferView) + " (" +
                 std::to_string(bv.byteLength) + " bytes)");
    }
    v.base = buffer.data.data() + bv.byteOffset + a.byteOffset;
    return v;
}

}  // namespace gc
