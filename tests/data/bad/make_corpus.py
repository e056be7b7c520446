#!/usr/bin/env python3
"""Writes the bad-scene corpus next to this script (the files are committed; rerun after
editing). Each file is small and breaks one rule; EXPECTED.txt says what geocold-cl must
answer. Deterministic: no randomness, so a rerun gives identical bytes."""
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    mode = "wb" if isinstance(data, (bytes, bytearray)) else "w"
    with open(os.path.join(HERE, name), mode, **({} if mode == "wb" else {"newline": "\n"})) as f:
        f.write(data)


# ---------------------------------------------------------------------------------- .obj
TRI = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
write("obj_truncated.obj", "# cut off mid-face by a failed download\n" + TRI + "f 1 2")
write("obj_truncated_vertex.obj", TRI + "v 0.5 0.")
write("obj_index_out_of_range.obj", TRI + "f 1 2 9\n")
write("obj_index_zero.obj", TRI + "f 0 1 2\n")
write("obj_index_malformed.obj", TRI + "f 1 2 three\n")
write("obj_index_slash_garbage.obj", TRI + "vt 0 0\nf 1/1 2/x 3/1\n")
write("obj_index_wraps_2pow32.obj", TRI + "f 1 2 4294967299\n")
write("obj_index_negative_out_of_range.obj", TRI + "f -1 -2 -4\n")
write("obj_normal_index_out_of_range.obj", TRI + "vn 0 0 1\nf 1//1 2//1 3//2\n")
write("obj_nan_coordinate.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")
write("obj_inf_coordinate.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n")
write("obj_float_overflow.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n")
write("obj_garbage_coordinate.obj", "v 0 0 0\nv 1 0x1g 0\nv 0 1 0\nf 1 2 3\n")
write("obj_nan_normal.obj", TRI + "vn 0 nan 1\nf 1//1 2//1 3//1\n")
write("obj_missing_coordinate.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n")
write("obj_empty.obj", "")
write("obj_comments_only.obj", "# nothing but comments\n\n# and blank lines\n")
write("obj_no_triangles.obj", TRI + "l 1 2 3\np 1\n")
write("obj_binary_garbage.obj", bytes((i * 167 + 13) % 256 for i in range(512)))
write("obj_missing_texture.obj", "mtllib obj_missing_texture.mtl\n" + TRI + "usemtl tex\nf 1 2 3\n")
write("obj_missing_texture.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd textures/not_there.png\n")
write("obj_unreadable_texture.obj", "mtllib obj_unreadable_texture.mtl\n" + TRI + "usemtl tex\nf 1 2 3\n")
write("obj_unreadable_texture.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd not_a_png.png\n")
write("not_a_png.png", b"\x89PNG\r\n\x1a\n" + b"this is not image data" * 4)
write("obj_texture_absurd_size.obj", "mtllib obj_texture_absurd_size.mtl\n" + TRI + "vt 0 0\nusemtl t\nf 1/1 2/1 3/1\n")
write("obj_texture_absurd_size.mtl", "newmtl t\nKd 1 1 1\nmap_Kd absurd_size.png\n")


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


# A PNG header claiming 60000 x 60000 RGBA (14 GB decoded) over a few bytes of data.
write("absurd_size.png", b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", 60000, 60000, 8, 6, 0, 0, 0)) +
      png_chunk(b"IDAT", zlib.compress(b"\0" * 64)) + png_chunk(b"IEND", b""))
write("obj_mtl_infinite_emission.obj", "mtllib obj_mtl_infinite_emission.mtl\n" + TRI + "usemtl hot\nf 1 2 3\n")
write("obj_mtl_infinite_emission.mtl", "newmtl hot\nKd 0.5 0.5 0.5\nKe 1e39 1 1\n")
# tinyobjloader reads "nan" and garbage in a .mtl as 0 without a word.
write("obj_mtl_nan_diffuse.obj", "mtllib obj_mtl_nan_diffuse.mtl\n" + TRI + "usemtl m\nf 1 2 3\n")
write("obj_mtl_nan_diffuse.mtl", "newmtl m\nKd nan 0.5 0.5\n")
write("obj_mtl_garbage_shininess.obj", "mtllib obj_mtl_garbage_shininess.mtl\n" + TRI + "usemtl m\nf 1 2 3\n")
write("obj_mtl_garbage_shininess.mtl", "newmtl m\nKd 0.5 0.5 0.5\nKs 0.1 0.1 0.1\nNs shiny\n")
# A library that is a device: reading /dev/stdin would block forever.
write("obj_mtllib_device.obj", "mtllib /dev/stdin\n" + TRI + "f 1 2 3\n")
# Nothing to render: every triangle has zero area (collinear, or all corners on one point).
write("obj_degenerate_only.obj",
      "# every triangle has zero area: collinear, or all corners on one point\n"
      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 1 1\nf 1 2 3\nf 4 4 4\nf 1 1 2\n")
# No single-precision camera frames these: it would stand past float's range (3.4e38), or
# so close to a scene 1e-3 across at z = 1e7 that its z rounds onto the scene's (ulp 1).
write("obj_extent_too_large.obj", "v -2e38 -2e38 -2e38\nv 2e38 -2e38 -2e38\nv 0 2e38 2e38\nf 1 2 3\n")
write("obj_tiny_far_from_origin.obj", "v 0 0 1e7\nv 1e-3 0 1e7\nv 0 1e-3 1e7\nf 1 2 3\n")
# Degenerate but valid: these must render (exit 0).
write("obj_missing_mtl.obj", "mtllib no_such_library.mtl\n" + TRI + "usemtl white\nf 1 2 3\n")
# Tiny and huge: float holds them, but the single-precision kernels would render them black
# (scene_checks.h), so they are refused with their extent.
write("obj_extent_1e-30.obj", "v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n")
write("obj_extent_1e30.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n")
write("obj_zero_area_and_duplicates.obj",
      "# a real quad, duplicated vertices, a repeated face and zero-area slivers\n"
      "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\n"
      "f 1 2 3 4\nf 5 6 7\nf 5 6 7\nf 1 5 2\nf 3 3 3\nf 1 2 6\n")

# ---------------------------------------------------------------------------------- glTF


def tri_bin(positions=None, indices=(0, 1, 2)):
    """One triangle: 3 VEC3 float positions (36 bytes), 3 normals (36), u16 indices (6+2 pad)."""
    positions = positions or [0, 0, 0, 1, 0, 0, 0, 1, 0]
    normals = [0, 0, 1] * 3
    return struct.pack("<18f", *positions, *normals) + struct.pack("<4H", *indices, 0)


def tri_doc(uri="tri_ok.bin", byte_length=80):
    buffer = {"byteLength": byte_length}
    if uri is not None:
        buffer["uri"] = uri
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "accessors": [
            {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 72},
            {"buffer": 0, "byteOffset": 72, "byteLength": 6},
        ],
        "buffers": [buffer],
    }


def gltf(name, doc):
    write(name, json.dumps(doc, indent=1) + "\n")


def glb(doc, bin_data, version=2, json_type=0x4E4F534A, bin_type=0x004E4942, total=None):
    """A .glb of the document and bin_data (None: no BIN chunk at all)."""
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), json_type) + text
    if bin_data is not None:
        bin_data = bytes(bin_data) + b"\0" * (-len(bin_data) % 4)
        body += struct.pack("<II", len(bin_data), bin_type) + bin_data
    length = 12 + len(body) if total is None else total
    return struct.pack("<III", 0x46546C67, version, length) + body


write("tri_ok.bin", tri_bin())
write("tri_nan.bin", tri_bin(positions=[0, 0, 0, float("nan"), 0, 0, 0, 1, 0]))
write("tri_inf.bin", tri_bin(positions=[0, 0, 0, 1, 0, 0, 0, float("inf"), 0]))
write("tri_bad_index.bin", tri_bin(indices=(0, 1, 7)))

ok_text = json.dumps(tri_doc(), indent=1)
write("gltf_truncated.gltf", ok_text[: len(ok_text) * 2 // 3])
write("gltf_empty.gltf", "")
write("gltf_binary_garbage.gltf", bytes((i * 89 + 7) % 256 for i in range(400)))
write("gltf_not_json.gltf", "<html><body>404 Not Found</body></html>\n")

d = tri_doc(); d["accessors"][0]["type"] = "VEC2"
gltf("gltf_position_vec2.gltf", d)
# UNSIGNED_INT positions: not glTF even with KHR_mesh_quantization (which allows 8/16-bit ones).
d = tri_doc(); d["accessors"][0]["componentType"] = 5125
gltf("gltf_position_uint.gltf", d)
d = tri_doc(); d["accessors"][2]["componentType"] = 5126
gltf("gltf_index_float.gltf", d)
d = tri_doc(); d["bufferViews"][0]["byteStride"] = 4
gltf("gltf_stride_too_small.gltf", d)
d = tri_doc(); d["bufferViews"][0]["byteStride"] = 40
gltf("gltf_stride_past_view.gltf", d)
d = tri_doc(); d["bufferViews"][0]["byteLength"] = 4096
gltf("gltf_bufferview_out_of_bounds.gltf", d)
d = tri_doc(); d["bufferViews"][1]["byteOffset"] = 78
gltf("gltf_bufferview_offset_out_of_bounds.gltf", d)
d = tri_doc(); d["bufferViews"][0]["buffer"] = 3
gltf("gltf_bufferview_bad_buffer.gltf", d)
d = tri_doc(); d["accessors"][0]["bufferView"] = 9
gltf("gltf_accessor_bad_bufferview.gltf", d)
d = tri_doc(); d["accessors"][0]["count"] = 4000000000
d["accessors"][1]["count"] = 4000000000
gltf("gltf_absurd_count.gltf", d)
d = tri_doc(); d["accessors"][2]["count"] = 4000000002
gltf("gltf_absurd_index_count.gltf", d)
d = tri_doc(); d["accessors"][0]["byteOffset"] = 68
gltf("gltf_accessor_offset_past_view.gltf", d)
d = tri_doc(); d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 12
gltf("gltf_accessor_index_out_of_range.gltf", d)
d = tri_doc(uri="tri_bad_index.bin")
gltf("gltf_index_out_of_range.gltf", d)
d = tri_doc(uri="tri_nan.bin")
gltf("gltf_nan_position.gltf", d)
d = tri_doc(uri="tri_inf.bin")
gltf("gltf_inf_position.gltf", d)
d = tri_doc(uri="missing_buffer.bin")
gltf("gltf_missing_bin.gltf", d)
d = tri_doc(byte_length=800)
gltf("gltf_buffer_longer_than_file.gltf", d)
d = tri_doc(uri="data:application/octet-stream;base64,@@@not base64@@@")
gltf("gltf_bad_data_uri.gltf", d)
d = tri_doc(); d["accessors"][2]["count"] = 2
d["bufferViews"][1]["byteLength"] = 4
gltf("gltf_index_count_not_multiple_of_3.gltf", d)
d = tri_doc(); d["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
gltf("gltf_node_cycle.gltf", d)
d = tri_doc(); d["nodes"][0]["mesh"] = 4
gltf("gltf_mesh_index_out_of_range.gltf", d)
d = tri_doc(); d["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1e39, 1]
gltf("gltf_infinite_transform.gltf", d)
d = tri_doc(); d["meshes"][0]["primitives"][0]["mode"] = 0
gltf("gltf_points_only.gltf", d)
d = tri_doc(); d["meshes"] = []; d["nodes"] = [{}]
gltf("gltf_no_meshes.gltf", d)
# 300 bytes of JSON naming 3000 instances of a mesh of 2^24 - 1 zero-filled vertices: 16.7
# billion triangles once flattened. Refused from the counts, before any instance is expanded.
d = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(3000))}],
     "nodes": [{"mesh": 0}] * 3000, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
     "accessors": [{"componentType": 5126, "count": 16777215, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}]}
gltf("gltf_instances_absurd_total.gltf", d)
d = tri_doc(); d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
d["textures"] = [{"source": 0}]
d["images"] = [{"uri": "textures/not_there.png"}]
gltf("gltf_missing_texture.gltf", d)
d = tri_doc(); d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
d["textures"] = [{"source": 0}]
d["images"] = [{"uri": "not_a_png.png"}]
gltf("gltf_unreadable_texture.gltf", d)
d = tri_doc(); d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
d["textures"] = [{"source": 0}]
d["images"] = [{"uri": "absurd_size.png"}]
gltf("gltf_texture_absurd_size.gltf", d)
d = tri_doc(); d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 5}}}]
gltf("gltf_texture_index_out_of_range.gltf", d)
d = tri_doc(); d["scene"] = 3
gltf("gltf_default_scene_out_of_range.gltf", d)
d = tri_doc(); d["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                                             "values": {"bufferView": 0}}
gltf("gltf_sparse_accessor.gltf", d)
# No bufferView means "all zeros" (spec), so no buffer bounds the count: 4e9 VEC3s = 48 GB.
gltf("gltf_accessor_without_bufferview_huge.gltf", {
    "asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"componentType": 5126, "count": 3999999999, "type": "VEC3"}]})
# Its only triangle has collinear corners: nothing to render.
write("tri_degenerate.bin", tri_bin(positions=[0, 0, 0, 1, 1, 1, 2, 2, 2]))
d = tri_doc(uri="tri_degenerate.bin")
gltf("gltf_degenerate_only.gltf", d)
# Conformance (the glTF 2.0 spec): a loader must refuse an asset whose major version it
# does not implement, whose minVersion is above its own, or that requires an extension it
# does not implement. An extension merely used is ignored, with a warning.
d = tri_doc(); d["asset"] = {"version": "1.0"}
gltf("gltf_version_1.gltf", d)
d = tri_doc(); d["asset"] = {"version": "2.1", "minVersion": "2.1"}
gltf("gltf_min_version_2_1.gltf", d)
d = tri_doc(); d["asset"] = {"version": "two"}
gltf("gltf_version_malformed.gltf", d)
d = tri_doc(); d["extensionsUsed"] = ["KHR_draco_mesh_compression", "KHR_materials_ior", "EXT_meshopt_compression"]
d["extensionsRequired"] = ["KHR_draco_mesh_compression", "KHR_materials_ior", "EXT_meshopt_compression"]
gltf("gltf_extension_required_unsupported.gltf", d)
d = tri_doc(); d["extensionsUsed"] = ["KHR_materials_ior"]; d["extensionsRequired"] = ["KHR_materials_ior"]
d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"extensions": {"KHR_materials_ior": {"ior": 1.33}}}]
gltf("gltf_extension_required_supported.gltf", d)
d = tri_doc(); d["extensionsUsed"] = ["KHR_materials_anisotropy", "KHR_materials_iridescence"]
d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.0}}}]
gltf("gltf_extension_used_unsupported.gltf", d)

# ---------------------------------------------------------------------------------- .glb
good = glb(tri_doc(uri=None), tri_bin())
write("glb_truncated_in_bin.glb", good[: len(good) - 20])
write("glb_truncated_header.glb", good[:10])
write("glb_truncated_chunk_header.glb", struct.pack("<III", 0x46546C67, 2, 14) + b"\x10\x00")
write("glb_length_field_past_end.glb", glb(tri_doc(uri=None), tri_bin(), total=len(good) + 4096))
write("glb_bad_magic.glb", b"gLTF" + good[4:])
write("glb_version_1.glb", glb(tri_doc(uri=None), tri_bin(), version=1))
write("glb_first_chunk_not_json.glb", glb(tri_doc(uri=None), tri_bin(), json_type=0x4E4942))
write("glb_second_chunk_not_bin.glb", glb(tri_doc(uri=None), tri_bin(), bin_type=0x12345678))
# A chunk length of 0xfffffff0: the 32-bit sum wraps if computed naively.
bad_len = bytearray(good)
struct.pack_into("<I", bad_len, 12, 0xFFFFFFF0)
write("glb_chunk_length_huge.glb", bytes(bad_len))
# The BIN chunk's length counts its own header (tinygltf 2.7's off-by-8).
bin_off = 12 + 8 + struct.unpack_from("<I", good, 12)[0]
off8 = bytearray(good)
struct.pack_into("<I", off8, bin_off, struct.unpack_from("<I", good, bin_off)[0] + 8)
write("glb_bin_chunk_length_plus_8.glb", bytes(off8))
write("glb_no_bin_chunk.glb", glb(tri_doc(uri=None), None))
write("glb_binary_garbage.glb", b"glTF" + bytes((i * 193 + 1) % 256 for i in range(200)))
write("glb_empty.glb", b"")
d = tri_doc(uri=None); d["accessors"][0]["count"] = 4000000000
write("glb_absurd_count.glb", glb(d, tri_bin()))
# A valid version-2 container holding a version-3 asset: the asset's version is checked too.
d = tri_doc(uri=None); d["asset"] = {"version": "3.0"}
write("glb_asset_version_3.glb", glb(d, tri_bin()))
d = tri_doc(uri=None); d["extensionsUsed"] = ["KHR_texture_basisu"]; d["extensionsRequired"] = ["KHR_texture_basisu"]
write("glb_extension_required_unsupported.glb", glb(d, tri_bin()))

# An embedded image whose bufferView starts at the end of the 80-byte buffer: tinygltf 2.7
# hands stb_image a pointer past the buffer without a bounds check (found by fuzz_gltf).
d = tri_doc(uri=None); d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
d["textures"] = [{"source": 0}]
d["images"] = [{"bufferView": 2, "mimeType": "image/png"}]
d["bufferViews"].append({"buffer": 0, "byteOffset": 80, "byteLength": 64})
write("glb_image_bufferview_out_of_bounds.glb", glb(d, tri_bin()))

# ---------------------------------------------------------------------------------- other
write("scene.fbx", "Kaydara FBX Binary\n")
write("scene_without_extension", TRI + "f 1 2 3\n")
os.makedirs(os.path.join(HERE, "directory.obj"), exist_ok=True)
write(os.path.join("directory.obj", ".keep"), "a directory named like a scene\n")
