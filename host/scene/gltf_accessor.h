// glTF accessors: each one checked against its bufferView and buffer, and against the types
// the spec allows for its use, before a byte of it is read; then its elements read back as
// floats or as indices.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace tinygltf {
class Model;
}  // namespace tinygltf

namespace gc {

// accessor.componentType values of glTF 2.0 (tinygltf's TINYGLTF_COMPONENT_TYPE_* equal them;
// gltf_accessor.cpp checks), here so that reading an element needs no tinygltf header.
enum GltfComponentType : int {
    kGltfByte = 5120,
    kGltfUnsignedByte = 5121,
    kGltfShort = 5122,
    kGltfUnsignedShort = 5123,
    kGltfUnsignedInt = 5125,
    kGltfFloat = 5126,
};

// What a mesh reads an accessor as. Each use allows what the spec allows for that attribute.
enum class AccessorUse { Position, Normal, TexCoord, Index, Tangent };

// Most elements an accessor without a bufferView (all zeros, so not bounded by the file's
// bytes) may claim: more than a real mesh needs, far less than a hostile count asks for.
inline constexpr std::size_t k_max_zero_elements = std::size_t{1} << 24;

// A checked accessor: `count` elements of `components` components each, `stride` bytes apart,
// all inside their buffer.
struct AccessorView {
    const unsigned char* base = nullptr; // first element; null = all zeros (no bufferView)
    std::size_t stride = 0;
    std::size_t count = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;

    // Component k of element i as a float (normalized integers map to [0,1] / [-1,1]).
    float get(std::size_t i, int k) const
    {
        if (!base) return 0.0f;
        const unsigned char* p = base + i * stride;
        switch (component_type) {
        case kGltfFloat: { float v; std::memcpy(&v, p + 4 * k, 4); return v; }
        case kGltfUnsignedByte: { const float v = p[k]; return normalized ? v / 255.0f : v; }
        case kGltfByte: {
            std::int8_t v; std::memcpy(&v, p + k, 1);
            return normalized ? std::fmax(v / 127.0f, -1.0f) : static_cast<float>(v);
        }
        case kGltfUnsignedShort: {
            std::uint16_t v; std::memcpy(&v, p + 2 * k, 2);
            return normalized ? v / 65535.0f : static_cast<float>(v);
        }
        case kGltfShort: {
            std::int16_t v; std::memcpy(&v, p + 2 * k, 2);
            return normalized ? std::fmax(v / 32767.0f, -1.0f) : static_cast<float>(v);
        }
        default: return 0.0f;
        }
    }

    std::uint32_t index(std::size_t i) const
    {
        if (!base) return 0;
        const unsigned char* p = base + i * stride;
        switch (component_type) {
        case kGltfUnsignedByte: return p[0];
        case kGltfUnsignedShort: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
        default: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
        }
    }
};

// Accessor `index` of `model`, checked for `use`. A failed check throws InputError
// "<file>: <where>, accessor <index>: <what is wrong>"; sparse accessors are refused.
AccessorView gltf_accessor_view(const tinygltf::Model& model, int index, AccessorUse use, const std::string& file,
                                const std::string& where);

}  // namespace gc
