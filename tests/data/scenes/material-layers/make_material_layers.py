#!/usr/bin/env python3
"""Writes MaterialLayers.gltf: five UV spheres in a row, lit by whatever the renderer adds (no
lights in the file), one material each: a plain dark-red glTF dielectric (roughness 0.2), the
same with KHR_materials_specular colour (1, 0.2, 0.2), with specular factor 0, with a smooth
KHR_materials_clearcoat (roughness 0.05) and with a half-strength rough coat (0.5, roughness
0.4). Written by
this script for the renderer's tests (no upstream); the buffer is embedded as a data URI.

    python3 make_material_layers.py   (in this folder)
"""
import base64
import json
import math
import struct

N_LAT, N_LON = 24, 48
pos, nrm, idx = [], [], []
for i in range(N_LAT + 1):
    th = math.pi * i / N_LAT
    for j in range(N_LON + 1):
        ph = 2.0 * math.pi * j / N_LON
        n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
        pos.append(n)
        nrm.append(n)
for i in range(N_LAT):
    for j in range(N_LON):
        a = i * (N_LON + 1) + j
        b = a + N_LON + 1
        idx += [a, b, a + 1, a + 1, b, b + 1]

blob = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm)
blob += b"".join(struct.pack("<H", k) for k in idx)
while len(blob) % 4:
    blob += b"\0"
nv = len(pos)
base = {"baseColorFactor": [0.5, 0.05, 0.03, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.2}
materials = [
    {"name": "plain", "pbrMetallicRoughness": base},
    {"name": "specular_red", "pbrMetallicRoughness": base,
     "extensions": {"KHR_materials_specular": {"specularFactor": 1.0, "specularColorFactor": [1.0, 0.2, 0.2]}}},
    {"name": "specular_off", "pbrMetallicRoughness": base,
     "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}},
    {"name": "coat_smooth", "pbrMetallicRoughness": dict(base, roughnessFactor=0.6),
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}},
    {"name": "coat_half_rough", "pbrMetallicRoughness": dict(base, roughnessFactor=0.6),
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.5, "clearcoatRoughnessFactor": 0.4}}},
]
doc = {
    "asset": {"version": "2.0", "generator": "make_material_layers.py"},
    "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_specular"],
    "scene": 0,
    "scenes": [{"nodes": list(range(len(materials)))}],
    "nodes": [{"mesh": k, "translation": [2.5 * (k - 2), 0.0, 0.0]} for k in range(len(materials))],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": k}]}
               for k in range(len(materials))],
    "materials": materials,
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
        {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
    ],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 12 * nv},
        {"buffer": 0, "byteOffset": 12 * nv, "byteLength": 12 * nv},
        {"buffer": 0, "byteOffset": 24 * nv, "byteLength": 2 * len(idx)},
    ],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
}
with open("MaterialLayers.gltf", "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
