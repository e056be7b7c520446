// glTF accessors (host/scene/gltf_accessor.h) on models built in memory: elements read back
// with strides and normalisation as the spec defines them, and every check that keeps a
// hostile accessor from reading outside its buffer.
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "host/scene/gltf_accessor.h"
#include "scene_test_util.h"

namespace gc {
namespace {

using test::expect_input_error;

// A model with one buffer of `bytes`, one bufferView over all of it (stride `stride`, 0 for
// tightly packed) and one accessor over that view.
tinygltf::Model one_accessor(std::vector<unsigned char> bytes, int type, int component_type, std::size_t count,
                             std::size_t stride = 0, bool normalized = false)
{
    tinygltf::Model m;
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = 0;
    view.byteLength = buffer.data.size();
    view.byteStride = stride;
    tinygltf::Accessor a;
    a.bufferView = 0;
    a.byteOffset = 0;
    a.type = type;
    a.componentType = component_type;
    a.count = count;
    a.normalized = normalized;
    m.buffers.push_back(buffer);
    m.bufferViews.push_back(view);
    m.accessors.push_back(a);
    return m;
}

template <typename T>
std::vector<unsigned char> bytes_of(std::initializer_list<T> values)
{
    std::vector<unsigned char> out(values.size() * sizeof(T));
    std::memcpy(out.data(), std::data(values), out.size());
    return out;
}

TEST(GltfAccessor, ReadsFloatsThroughAStride)
{
    // Two VEC3 positions 16 bytes apart (a fourth float of padding each).
    const auto m = one_accessor(bytes_of<float>({1, 2, 3, -99, 4, 5, 6, -99}), TINYGLTF_TYPE_VEC3,
                                TINYGLTF_COMPONENT_TYPE_FLOAT, 2, 16);
    const AccessorView v = gltf_accessor_view(m, 0, AccessorUse::Position, "s.gltf", "mesh 0");
    ASSERT_EQ(v.count, 2u);
    EXPECT_EQ(v.stride, 16u);
    EXPECT_EQ(v.get(0, 2), 3.0f);
    EXPECT_EQ(v.get(1, 0), 4.0f);
    EXPECT_EQ(v.get(1, 2), 6.0f);
}

TEST(GltfAccessor, NormalizedTexcoordsMapToTheUnitInterval)
{
    // glTF 2.0's normalised integers: u8 c / 255, u16 c / 65535.
    const auto u8 = one_accessor({0, 255, 51, 0}, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 2, 0, true);
    const AccessorView a = gltf_accessor_view(u8, 0, AccessorUse::TexCoord, "s.gltf", "mesh 0");
    EXPECT_EQ(a.get(0, 0), 0.0f);
    EXPECT_EQ(a.get(0, 1), 1.0f);
    EXPECT_FLOAT_EQ(a.get(1, 0), 0.2f);
    const auto u16 = one_accessor(bytes_of<std::uint16_t>({65535, 0}), TINYGLTF_TYPE_VEC2,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 1, 0, true);
    const AccessorView b = gltf_accessor_view(u16, 0, AccessorUse::TexCoord, "s.gltf", "mesh 0");
    EXPECT_EQ(b.get(0, 0), 1.0f);
    EXPECT_EQ(b.get(0, 1), 0.0f);
}

TEST(GltfAccessor, SignedNormalizedComponentsClampAtMinusOne)
{
    // max(c / 127, -1): -128 and -127 are both -1 (a view built by hand: four components).
    const std::vector<unsigned char> bytes = {0x80, 0x81, 0x7f, 0x00};
    AccessorView v;
    v.base = bytes.data();
    v.stride = 4;
    v.count = 1;
    v.component_type = kGltfByte;
    v.components = 4;
    v.normalized = true;
    EXPECT_EQ(v.get(0, 0), -1.0f);
    EXPECT_EQ(v.get(0, 1), -1.0f);
    EXPECT_EQ(v.get(0, 2), 1.0f);
    EXPECT_EQ(v.get(0, 3), 0.0f);
}

TEST(GltfAccessor, IndicesOfEveryWidth)
{
    const auto u8 = one_accessor({7, 250}, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 2);
    EXPECT_EQ(gltf_accessor_view(u8, 0, AccessorUse::Index, "s.gltf", "m").index(1), 250u);
    const auto u16 = one_accessor(bytes_of<std::uint16_t>({1, 60000}), TINYGLTF_TYPE_SCALAR,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 2);
    EXPECT_EQ(gltf_accessor_view(u16, 0, AccessorUse::Index, "s.gltf", "m").index(1), 60000u);
    const auto u32 = one_accessor(bytes_of<std::uint32_t>({1, 4000000000u}), TINYGLTF_TYPE_SCALAR,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, 2);
    EXPECT_EQ(gltf_accessor_view(u32, 0, AccessorUse::Index, "s.gltf", "m").index(1), 4000000000u);
}

TEST(GltfAccessor, NoBufferViewMeansZerosUpToALimit)
{
    tinygltf::Model m = one_accessor({}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, 3);
    m.accessors[0].bufferView = -1;
    const AccessorView v = gltf_accessor_view(m, 0, AccessorUse::Normal, "s.gltf", "mesh 0");
    EXPECT_EQ(v.base, nullptr);
    EXPECT_EQ(v.get(2, 1), 0.0f);
    m.accessors[0].count = k_max_zero_elements + 1;
    expect_input_error([&] { gltf_accessor_view(m, 0, AccessorUse::Normal, "s.gltf", "mesh 0"); },
                       {"s.gltf: mesh 0, accessor 0: ", "no bufferView", "is refused"});
}

TEST(GltfAccessor, RefusesWhatWouldReadOutsideTheBuffer)
{
    const auto good = one_accessor(bytes_of<float>({0, 0, 0, 1, 0, 0}), TINYGLTF_TYPE_VEC3,
                                   TINYGLTF_COMPONENT_TYPE_FLOAT, 2);
    const auto fails = [&](tinygltf::Model m, std::initializer_list<std::string> parts) {
        expect_input_error([&] { gltf_accessor_view(m, 0, AccessorUse::Position, "s.gltf", "mesh 0"); }, parts);
    };
    tinygltf::Model m = good;
    m.accessors[0].count = 3;  // 36 bytes from a 24-byte view
    fails(m, {"s.gltf: mesh 0, accessor 0: ", "3 elements of 12 bytes", "run past the end of bufferView 0"});
    m = good;
    m.accessors[0].byteOffset = 4;  // the second element's last float leaves the view
    fails(m, {"from byte 4", "run past the end"});
    m = good;
    m.accessors[0].count = std::numeric_limits<std::size_t>::max();  // no overflow on the way
    fails(m, {"run past the end"});
    m = good;
    m.bufferViews[0].byteLength = 100;  // a view longer than its buffer
    fails(m, {"bufferView 0", "runs past the end of buffer 0 (24 bytes)"});
    m = good;
    m.bufferViews[0].byteStride = 8;  // smaller than a VEC3 FLOAT
    fails(m, {"byteStride 8 is smaller than an element (12 bytes)"});
    m = good;
    m.accessors[0].bufferView = 5;
    fails(m, {"bufferView 5 out of range (1 bufferViews)"});
    m = good;
    m.bufferViews[0].buffer = 2;
    fails(m, {"names buffer 2, out of range (1 buffers)"});
    m = good;
    m.accessors[0].sparse.isSparse = true;
    fails(m, {"sparse accessors are not supported"});
    expect_input_error([&] { gltf_accessor_view(good, 1, AccessorUse::Position, "s.gltf", "mesh 0"); },
                       {"s.gltf: mesh 0: accessor index 1 out of range (1 accessors)"});
}

TEST(GltfAccessor, EachUseAllowsOnlyTheSpecsTypes)
{
    const auto floats = one_accessor(bytes_of<float>({0, 0, 0, 0}), TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT, 2);
    EXPECT_NO_THROW(gltf_accessor_view(floats, 0, AccessorUse::TexCoord, "s.gltf", "m"));
    expect_input_error([&] { gltf_accessor_view(floats, 0, AccessorUse::Position, "s.gltf", "m"); },
                       {"VEC2 FLOAT where VEC3 FLOAT or"});
    expect_input_error([&] { gltf_accessor_view(floats, 0, AccessorUse::Index, "s.gltf", "m"); },
                       {"where SCALAR UNSIGNED_BYTE/SHORT/INT is required"});
    // Normals as integers must be normalised and signed (KHR_mesh_quantization).
    const auto bytes3 = one_accessor({0, 0, 0, 0}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 1, 4, true);
    expect_input_error([&] { gltf_accessor_view(bytes3, 0, AccessorUse::Normal, "s.gltf", "m"); },
                       {"VEC3 UNSIGNED_BYTE (normalized) where VEC3 FLOAT or (KHR_mesh_quantization) normalized BYTE/SHORT"});
    const auto signed3 = one_accessor({0, 0, 0, 0}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_BYTE, 1, 4, false);
    expect_input_error([&] { gltf_accessor_view(signed3, 0, AccessorUse::Normal, "s.gltf", "m"); },
                       {"VEC3 BYTE where VEC3 FLOAT or (KHR_mesh_quantization) normalized BYTE/SHORT"});
    // A normalized FLOAT is not glTF.
    auto normalized_floats = floats;
    normalized_floats.accessors[0].normalized = true;
    expect_input_error([&] { gltf_accessor_view(normalized_floats, 0, AccessorUse::TexCoord, "s.gltf", "m"); },
                       {"VEC2 FLOAT (normalized) where"});
    const auto vec3 = one_accessor(bytes_of<float>({0, 0, 0}), TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, 1);
    expect_input_error([&] { gltf_accessor_view(vec3, 0, AccessorUse::Tangent, "s.gltf", "m"); },
                       {"VEC3 FLOAT where VEC4 FLOAT or"});
}

// KHR_mesh_quantization: every integer type the extension allows, per attribute, read back by
// the spec's formulas (unsigned c / (2^n - 1), signed max(c / (2^(n-1) - 1), -1); not
// normalised: the integer itself).
TEST(GltfAccessor, QuantizedPositionsOfEveryIntegerType)
{
    // VEC3 of bytes padded to 4-byte elements, as the spec's alignment rule asks.
    const auto b = one_accessor({0xff, 0x02, 0x80, 0x00}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_BYTE, 1, 4);
    const AccessorView vb = gltf_accessor_view(b, 0, AccessorUse::Position, "s.gltf", "m");
    EXPECT_EQ(vb.get(0, 0), -1.0f);
    EXPECT_EQ(vb.get(0, 1), 2.0f);
    EXPECT_EQ(vb.get(0, 2), -128.0f);
    const auto ub = one_accessor({0xff, 0x02, 0x80, 0x00}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 1, 4);
    EXPECT_EQ(gltf_accessor_view(ub, 0, AccessorUse::Position, "s.gltf", "m").get(0, 0), 255.0f);
    const auto ubn = one_accessor({0xff, 0x33, 0x00, 0x00}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 1, 4, true);
    EXPECT_EQ(gltf_accessor_view(ubn, 0, AccessorUse::Position, "s.gltf", "m").get(0, 0), 1.0f);
    EXPECT_EQ(gltf_accessor_view(ubn, 0, AccessorUse::Position, "s.gltf", "m").get(0, 1), 0x33 / 255.0f);
    const auto s16 = one_accessor(bytes_of<std::int16_t>({-300, 7, 32767, 0}), TINYGLTF_TYPE_VEC3,
                                  TINYGLTF_COMPONENT_TYPE_SHORT, 1, 8);
    const AccessorView vs = gltf_accessor_view(s16, 0, AccessorUse::Position, "s.gltf", "m");
    EXPECT_EQ(vs.get(0, 0), -300.0f);
    EXPECT_EQ(vs.get(0, 2), 32767.0f);
    const auto s16n = one_accessor(bytes_of<std::int16_t>({-32768, -32767, 16384, 0}), TINYGLTF_TYPE_VEC3,
                                   TINYGLTF_COMPONENT_TYPE_SHORT, 1, 8, true);
    const AccessorView vsn = gltf_accessor_view(s16n, 0, AccessorUse::Position, "s.gltf", "m");
    EXPECT_EQ(vsn.get(0, 0), -1.0f);
    EXPECT_EQ(vsn.get(0, 1), -1.0f);
    EXPECT_EQ(vsn.get(0, 2), 16384 / 32767.0f);
    const auto u16 = one_accessor(bytes_of<std::uint16_t>({65535, 1, 2, 0}), TINYGLTF_TYPE_VEC3,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 1, 8);
    EXPECT_EQ(gltf_accessor_view(u16, 0, AccessorUse::Position, "s.gltf", "m").get(0, 0), 65535.0f);
    const auto u16n = one_accessor(bytes_of<std::uint16_t>({65535, 0, 0, 0}), TINYGLTF_TYPE_VEC3,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 1, 8, true);
    EXPECT_EQ(gltf_accessor_view(u16n, 0, AccessorUse::Position, "s.gltf", "m").get(0, 0), 1.0f);
}

TEST(GltfAccessor, QuantizedNormalsAndTangentsAreSignedNormalized)
{
    const auto nb = one_accessor({0x81, 0x7f, 0x80, 0x00}, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_BYTE, 1, 4, true);
    const AccessorView n = gltf_accessor_view(nb, 0, AccessorUse::Normal, "s.gltf", "m");
    EXPECT_EQ(n.get(0, 0), -1.0f);  // -127 / 127
    EXPECT_EQ(n.get(0, 1), 1.0f);
    EXPECT_EQ(n.get(0, 2), -1.0f);  // -128 clamps to -1
    const auto ns = one_accessor(bytes_of<std::int16_t>({-32768, 32767, 100, 0}), TINYGLTF_TYPE_VEC3,
                                 TINYGLTF_COMPONENT_TYPE_SHORT, 1, 8, true);
    const AccessorView s = gltf_accessor_view(ns, 0, AccessorUse::Normal, "s.gltf", "m");
    EXPECT_EQ(s.get(0, 0), -1.0f);
    EXPECT_EQ(s.get(0, 1), 1.0f);
    EXPECT_EQ(s.get(0, 2), 100 / 32767.0f);
    const auto tb = one_accessor({0x7f, 0x00, 0x00, 0x81}, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_BYTE, 1, 0, true);
    const AccessorView t = gltf_accessor_view(tb, 0, AccessorUse::Tangent, "s.gltf", "m");
    EXPECT_EQ(t.get(0, 0), 1.0f);
    EXPECT_EQ(t.get(0, 3), -1.0f);
    const auto ts = one_accessor(bytes_of<std::int16_t>({0, 32767, 0, 32767}), TINYGLTF_TYPE_VEC4,
                                 TINYGLTF_COMPONENT_TYPE_SHORT, 1, 0, true);
    EXPECT_EQ(gltf_accessor_view(ts, 0, AccessorUse::Tangent, "s.gltf", "m").get(0, 1), 1.0f);
    const auto unnormalized = one_accessor(bytes_of<std::int16_t>({0, 1, 0, 1}), TINYGLTF_TYPE_VEC4,
                                           TINYGLTF_COMPONENT_TYPE_SHORT, 1);
    expect_input_error([&] { gltf_accessor_view(unnormalized, 0, AccessorUse::Tangent, "s.gltf", "mesh 2"); },
                       {"s.gltf: mesh 2, accessor 0: VEC4 SHORT where VEC4 FLOAT or (KHR_mesh_quantization) normalized"});
}

TEST(GltfAccessor, QuantizedTexcoordsOfEveryIntegerType)
{
    const auto b = one_accessor({0xfd, 0x05}, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_BYTE, 1);
    EXPECT_EQ(gltf_accessor_view(b, 0, AccessorUse::TexCoord, "s.gltf", "m").get(0, 0), -3.0f);
    const auto bn = one_accessor({0x81, 0x40}, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_BYTE, 1, 0, true);
    const AccessorView vbn = gltf_accessor_view(bn, 0, AccessorUse::TexCoord, "s.gltf", "m");
    EXPECT_EQ(vbn.get(0, 0), -1.0f);
    EXPECT_EQ(vbn.get(0, 1), 64 / 127.0f);
    const auto ub = one_accessor({200, 0}, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 1);
    EXPECT_EQ(gltf_accessor_view(ub, 0, AccessorUse::TexCoord, "s.gltf", "m").get(0, 0), 200.0f);
    const auto sn = one_accessor(bytes_of<std::int16_t>({-32768, 32767}), TINYGLTF_TYPE_VEC2,
                                 TINYGLTF_COMPONENT_TYPE_SHORT, 1, 0, true);
    const AccessorView vsn = gltf_accessor_view(sn, 0, AccessorUse::TexCoord, "s.gltf", "m");
    EXPECT_EQ(vsn.get(0, 0), -1.0f);
    EXPECT_EQ(vsn.get(0, 1), 1.0f);
    const auto us = one_accessor(bytes_of<std::uint16_t>({1000, 2}), TINYGLTF_TYPE_VEC2,
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 1);
    EXPECT_EQ(gltf_accessor_view(us, 0, AccessorUse::TexCoord, "s.gltf", "m").get(0, 0), 1000.0f);
}

}  // namespace
}  // namespace gc
