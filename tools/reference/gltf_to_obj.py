"""Converts a glTF 2.0 file (.gltf or .glb) to OBJ + MTL for the reference renderer.

Only what geocold-cl renders today survives the trip:
  * triangle primitives (mode 4) of every node of the default scene, with the node hierarchy's
    transforms applied (matrix or TRS); a transform that mirrors flips the winding back;
  * POSITION, NORMAL (inverse-transpose transformed) and TEXCOORD_0; uvs are written as OBJ's
    (u, 1 - v) so that the OBJ reader's flip restores glTF's (0, 0) = top-left;
  * materials become Lambert with Kd = baseColorFactor (linear) and map_Kd = baseColorTexture,
    plus Ke = emissiveFactor (times KHR_materials_emissive_strength).
By default metallic and roughness are dropped (a Lambert reference checks geometry, transforms,
uvs and textures). With pbr=True (make_reference.py --pbr) each material also gets the PBR-MTL
keys Pm / Pr (metallicFactor / roughnessFactor), map_Pmr (glTF's packed metallicRoughness
texture) and norm (normalTexture), which mitsuba_scene.py maps to Mitsuba's `principled`.

Two kinds of glTF material become more than Lambert, in either mode (the Lambert reference
would misrepresent them): full KHR_materials_transmission (transmissionFactor 1, no
transmission texture) becomes a dielectric, with the key Ptr (its KHR_materials_ior) and, for a
KHR_materials_volume, Pabs with the absorption coefficients -ln(attenuationColor) /
attenuationDistance (zeros without an attenuation; smooth without a volume it is thin-walled);
a metal (metallicFactor 1, not transmissive) becomes a conductor, with the key Pmetal. Both get
Pgr, the roughnessFactor, and map_Pgr, the metallicRoughness texture (its G the roughness;
mitsuba_scene.py keeps a dielectric only where its B, the metallic, is 0 throughout, and a
metal where it is 1). Kd stays the base colour: what a dielectric tints, what a metal reflects.
Other transmission (or metallic between 0 and 1) stays Lambert, with a warning.
"""

from __future__ import annotations

import base64
import json
import math
import os
import struct

import numpy as np

_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
_DTYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}


class Gltf:
    def __init__(self, path: str):
        self.path = path
        self.base = os.path.dirname(path)
        with open(path, "rb") as f:
            data = f.read()
        self.glb_bin = None
        if data[:4] == b"glTF":
            # GLB: 12-byte header, then chunks (length, type, payload): JSON first, BIN optional.
            offset = 12
            chunks = {}
            while offset + 8 <= len(data):
                length, kind = struct.unpack_from("<II", data, offset)
                chunks[kind] = data[offset + 8 : offset + 8 + length]
                offset += 8 + length
            self.doc = json.loads(chunks[0x4E4F534A].decode("utf-8"))
            self.glb_bin = chunks.get(0x004E4942)
        else:
            self.doc = json.loads(data.decode("utf-8"))
        self._buffers = {}

    def buffer(self, index: int) -> bytes:
        if index not in self._buffers:
            uri = self.doc["buffers"][index].get("uri")
            if uri is None:
                self._buffers[index] = self.glb_bin
            elif uri.startswith("data:"):
                self._buffers[index] = base64.b64decode(uri.split(",", 1)[1])
            else:
                with open(os.path.join(self.base, uri), "rb") as f:
                    self._buffers[index] = f.read()
        return self._buffers[index]

    def view_bytes(self, index: int) -> bytes:
        view = self.doc["bufferViews"][index]
        start = view.get("byteOffset", 0)
        return self.buffer(view["buffer"])[start : start + view["byteLength"]]

    def accessor(self, index: int) -> np.ndarray:
        acc = self.doc["accessors"][index]
        if "sparse" in acc:
            raise ValueError(f"{self.path}: accessor {index}: sparse accessors are not supported")
        dtype = np.dtype(_DTYPES[acc["componentType"]])
        comps = _COMPONENTS[acc["type"]]
        count = acc["count"]
        view = self.doc["bufferViews"][acc["bufferView"]]
        raw = self.view_bytes(acc["bufferView"])
        stride = view.get("byteStride") or dtype.itemsize * comps
        start = acc.get("byteOffset", 0)
        rows = np.ndarray((count, comps), dtype=dtype, buffer=raw, offset=start, strides=(stride, dtype.itemsize))
        out = rows.astype(np.float64)
        if acc.get("normalized") and dtype.kind in "iu":
            out = np.maximum(out / np.iinfo(dtype).max, -1.0)
        return out

    def image_file(self, image_index: int, out_dir: str) -> str:
        image = self.doc["images"][image_index]
        if "uri" in image and not image["uri"].startswith("data:"):
            return os.path.normpath(os.path.join(self.base, image["uri"]))
        data = base64.b64decode(image["uri"].split(",", 1)[1]) if "uri" in image else self.view_bytes(image["bufferView"])
        ext = ".jpg" if image.get("mimeType") == "image/jpeg" else ".png"
        path = os.path.join(out_dir, f"image_{image_index}{ext}")
        with open(path, "wb") as f:
            f.write(data)
        return path


def _node_matrix(node: dict) -> np.ndarray:
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T  # glTF is column-major
    t = np.eye(4)
    t[:3, 3] = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.eye(4)
    r[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    s = np.diag(list(node.get("scale", [1, 1, 1])) + [1.0])
    return t @ r @ s


def _texture_file(gltf: Gltf, tex: dict, out_dir: str) -> str:
    texture = gltf.doc["textures"][tex["index"]]
    return os.path.abspath(gltf.image_file(texture["source"], out_dir))


def _write_glossy(f, gltf: "Gltf", out_dir: str, index: int, mat: dict) -> bool:
    """The keys of a dielectric or metal (the module's docstring); False for any other material."""
    ext = mat.get("extensions", {})
    pbr = mat.get("pbrMetallicRoughness", {})
    transmission = ext.get("KHR_materials_transmission", {})
    where = f"{gltf.path}: material {index} ({mat.get('name', '')})"
    if transmission.get("transmissionFactor", 0.0) > 0.0:
        if (transmission["transmissionFactor"] != 1.0 or "transmissionTexture" in transmission
                or ("metallicRoughnessTexture" not in pbr and pbr.get("metallicFactor", 1.0) != 0.0)):
            print(f"warning: {where}: only full, non-metal transmission becomes a dielectric; this one stays Lambert")
            return False
        f.write(f"Ptr {ext.get('KHR_materials_ior', {}).get('ior', 1.5)}\n")
        volume = ext.get("KHR_materials_volume")
        if volume is not None and volume.get("thicknessFactor", 0.0) > 0.0:
            distance = volume.get("attenuationDistance", math.inf)
            colour = volume.get("attenuationColor", [1.0, 1.0, 1.0])
            sigma = [0.0 if math.isinf(distance) else -math.log(max(c, 1e-30)) / distance for c in colour]
            f.write(f"Pabs {sigma[0]:.9g} {sigma[1]:.9g} {sigma[2]:.9g}\n")
    elif pbr.get("metallicFactor", 1.0) == 1.0:
        f.write("Pmetal\n")
    else:
        return False
    f.write(f"Pgr {pbr.get('roughnessFactor', 1.0)}\n")
    if "metallicRoughnessTexture" in pbr:
        f.write(f"map_Pgr {_texture_file(gltf, pbr['metallicRoughnessTexture'], out_dir)}\n")
    return True


def _write_mtl(gltf: Gltf, path: str, out_dir: str, pbr_mode: bool = False) -> list[str]:
    names = []
    with open(path, "w") as f:
        for i, mat in enumerate(gltf.doc.get("materials", [])):
            name = f"m{i}"
            names.append(name)
            pbr = mat.get("pbrMetallicRoughness", {})
            color = pbr.get("baseColorFactor", [1, 1, 1, 1])
            strength = mat.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1)
            ke = [c * strength for c in mat.get("emissiveFactor", [0, 0, 0])]
            f.write(f"newmtl {name}\nillum 1\nKd {color[0]} {color[1]} {color[2]}\nKe {ke[0]} {ke[1]} {ke[2]}\n")
            glossy = not pbr_mode and _write_glossy(f, gltf, out_dir, i, mat)
            if pbr.get("metallicFactor", 1.0) > 0 and not pbr_mode and not glossy:
                print(f"warning: {gltf.path}: material {i} ({mat.get('name', '')}) has metallic "
                      f"{pbr.get('metallicFactor', 1.0)}; rendered as Lambert baseColor (geocold-cl's PBR stub)")
            tex = pbr.get("baseColorTexture")
            if tex is not None:
                if tex.get("texCoord", 0) != 0:
                    print(f"warning: {gltf.path}: material {i}: texCoord {tex['texCoord']} treated as 0")
                texture = gltf.doc["textures"][tex["index"]]
                sampler = gltf.doc.get("samplers", [{}])[texture["sampler"]] if "sampler" in texture else {}
                if sampler.get("wrapS", 10497) != 10497 or sampler.get("wrapT", 10497) != 10497:
                    print(f"warning: {gltf.path}: material {i}: only REPEAT wrapping is reproduced")
                f.write(f"map_Kd {os.path.abspath(gltf.image_file(texture['source'], out_dir))}\n")
            if pbr_mode:
                f.write(f"Pm {pbr.get('metallicFactor', 1.0)}\nPr {pbr.get('roughnessFactor', 1.0)}\n")
                if "metallicRoughnessTexture" in pbr:
                    f.write(f"map_Pmr {_texture_file(gltf, pbr['metallicRoughnessTexture'], out_dir)}\n")
                if "normalTexture" in mat:
                    if mat["normalTexture"].get("scale", 1.0) != 1.0:
                        print(f"warning: {gltf.path}: material {i}: normalTexture.scale ignored (as geocold-cl does)")
                    f.write(f"norm {_texture_file(gltf, mat['normalTexture'], out_dir)}\n")
            f.write("\n")
    return names


def convert(path: str, out_dir: str, pbr: bool = False) -> str:
    """Writes OUT_DIR/<stem>.obj (+ .mtl, + embedded images) and returns the .obj path."""
    gltf = Gltf(path)
    os.makedirs(out_dir, exist_ok=True)
    stem = os.path.splitext(os.path.basename(path))[0]
    mtl_names = _write_mtl(gltf, os.path.join(out_dir, stem + ".mtl"), out_dir, pbr)
    doc = gltf.doc
    scene_index = doc.get("scene", 0)
    roots = doc["scenes"][scene_index]["nodes"] if doc.get("scenes") else list(range(len(doc.get("nodes", []))))
    lines = [f"mtllib {stem}.mtl\n"]
    counts = {"v": 0, "vt": 0, "vn": 0}

    def visit(node_index: int, parent: np.ndarray):
        node = doc["nodes"][node_index]
        world = parent @ _node_matrix(node)
        if "mesh" in node:
            emit_mesh(doc["meshes"][node["mesh"]], world)
        for child in node.get("children", []):
            visit(child, world)

    def emit_mesh(mesh: dict, world: np.ndarray):
        normal_matrix = np.linalg.inv(world[:3, :3]).T
        flip = np.linalg.det(world[:3, :3]) < 0
        for prim in mesh["primitives"]:
            if prim.get("mode", 4) != 4:
                print(f"warning: {path}: a primitive of mode {prim['mode']} is skipped (triangles only)")
                continue
            attrs = prim["attributes"]
            pos = gltf.accessor(attrs["POSITION"])
            pos = pos @ world[:3, :3].T + world[:3, 3]
            nrm = None
            if "NORMAL" in attrs:
                nrm = gltf.accessor(attrs["NORMAL"]) @ normal_matrix.T
                nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-30)
            uv = gltf.accessor(attrs["TEXCOORD_0"]) if "TEXCOORD_0" in attrs else None
            idx = gltf.accessor(prim["indices"]).astype(np.int64).ravel() if "indices" in prim else np.arange(len(pos))
            tris = idx[: len(idx) // 3 * 3].reshape(-1, 3)
            if flip:
                tris = tris[:, [0, 2, 1]]
            material = prim.get("material")
            lines.append(f"usemtl {mtl_names[material]}\n" if material is not None else "usemtl __default__\n")
            lines.extend(f"v {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n" for p in pos)
            if uv is not None:
                lines.extend(f"vt {t[0]:.9g} {1.0 - t[1]:.9g}\n" for t in uv)
            if nrm is not None:
                lines.extend(f"vn {n[0]:.9g} {n[1]:.9g} {n[2]:.9g}\n" for n in nrm)
            v0, t0, n0 = counts["v"] + 1, counts["vt"] + 1, counts["vn"] + 1
            for tri in tris:
                corners = []
                for k in tri:
                    c = f"{v0 + k}/"
                    c += f"{t0 + k}" if uv is not None else ""
                    c += f"/{n0 + k}" if nrm is not None else ""
                    corners.append(c.rstrip("/"))
                lines.append("f " + " ".join(corners) + "\n")
            counts["v"] += len(pos)
            counts["vt"] += len(uv) if uv is not None else 0
            counts["vn"] += len(nrm) if nrm is not None else 0

    for root in roots:
        visit(root, np.eye(4))
    if counts["v"] == 0:
        raise ValueError(f"{path}: no triangle primitives")
    obj_path = os.path.join(out_dir, stem + ".obj")
    with open(obj_path, "w") as f:
        f.writelines(lines)
    return obj_path
