#!/usr/bin/env python3
"""Writes the synthetic part of the fuzz seed corpus (corpus/obj, corpus/gltf); the repo's
Cornell boxes are copied in as well. Deterministic; rerun after editing."""
import base64
import json
import os
import shutil
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
OBJ = os.path.join(HERE, "corpus", "obj")
GLTF = os.path.join(HERE, "corpus", "gltf")
os.makedirs(OBJ, exist_ok=True)
os.makedirs(GLTF, exist_ok=True)


def write(folder, name, data):
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


# ---------------------------------------------------------------------------- .obj seeds
for name in ("CornellBox-Original.obj", "CornellBox-Mirror.obj"):
    shutil.copy(os.path.join(ROOT, "scenes", "cornell-box", name), os.path.join(OBJ, name))
write(OBJ, "quad_negative_crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf -4 -3 -2 -1\r\n")
write(OBJ, "normals_uvs.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "o tri\ng group\ns 1\nf 1/1/1 2/2/1 3/3/1\nf 1//1 2//1 3//1\nf 1/1 2/2 3/3\n")
# The input is at in.obj: "mtllib in.obj" makes the fuzzer's bytes the material library too.
write(OBJ, "self_mtllib.obj",
      "mtllib in.obj\nnewmtl red\nKd 0.8 0.1 0.1\nKs 0.2 0.2 0.2\nNs 20\nillum 2\n"
      "newmtl glass\nillum 7\nNi 1.5\nd 0.5\nnewmtl lamp\nKe 10 10 10\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nusemtl red\nf 1 2 3\nusemtl glass\nf 2 4 3\nusemtl lamp\nf 1 2 4\n")
write(OBJ, "pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n")


# ---------------------------------------------------------------------------- glTF seeds
def tri_bin():
    return struct.pack("<18f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1) + \
        struct.pack("<6f", 0, 0, 1, 0, 0, 1) + struct.pack("<4H", 0, 1, 2, 0)


def tri_doc(buffer):
    return {
        "asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0, "translation": [0, 0, -2], "children": [3]},
                  {"camera": 0, "translation": [0, 0, 3]},
                  {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0]},
                  {"mesh": 0, "scale": [-1, 1, 1], "rotation": [0, 0.7071, 0, 0.7071]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5}]}},
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1], "metallicFactor": 0.1},
                       "emissiveFactor": [0, 0, 0], "doubleSided": True}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                    "indices": 3, "material": 0}]}],
        "accessors": [
            {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                        {"buffer": 0, "byteOffset": 72, "byteLength": 24},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 6}],
        "buffers": [buffer],
    }


def glb(doc, bin_data):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    bin_data += b"\0" * (-len(bin_data) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(bin_data), 0x004E4942) + bin_data
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def png_2x2():
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"\0\xff\0\0\0\xff\0" + b"\0\0\0\xff\xff\xff\xff"
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0)) + \
        chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


b = tri_bin()
uri = "data:application/octet-stream;base64," + base64.b64encode(b).decode()
write(GLTF, "tri_data_uri.gltf", json.dumps(tri_doc({"uri": uri, "byteLength": len(b)}), indent=1))
write(GLTF, "tri.glb", glb(tri_doc({"byteLength": len(b)}), b))

# A textured triangle: the PNG lives in the BIN chunk behind a bufferView.
png = png_2x2()
tb = b + b"\0" * (-len(b) % 4)
doc = tri_doc({"byteLength": len(tb) + len(png)})
doc["bufferViews"].append({"buffer": 0, "byteOffset": len(tb), "byteLength": len(png)})
doc["images"] = [{"bufferView": 3, "mimeType": "image/png"}]
doc["samplers"] = [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33648}]
doc["textures"] = [{"source": 0, "sampler": 0}]
doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
doc["materials"][0]["normalTexture"] = {"index": 0, "texCoord": 1}
write(GLTF, "tri_textured.glb", glb(doc, tb + png))

# Non-indexed, a matrix node, u8 indices in a second primitive, an unsupported mode.
doc = tri_doc({"uri": uri, "byteLength": len(b)})
doc["nodes"][0] = {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1]}
doc["meshes"][0]["primitives"].append({"attributes": {"POSITION": 0}})
doc["meshes"][0]["primitives"].append({"attributes": {"POSITION": 0}, "mode": 1})
write(GLTF, "tri_matrix_nonindexed.gltf", json.dumps(doc))
