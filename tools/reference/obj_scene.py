"""Reads a Wavefront OBJ (+ its MTL files) into triangle groups, one per material.

Follows the conventions of the reference images (/work/shared/refs/README.md), which are also
what geocold-cl's loader does:
  * faces are fan-triangulated: (0, k, k + 1);
  * a triangle whose three corners all have `vn` is smooth-shaded with them, any other gets
    its flat (winding) normal at every corner;
  * OBJ texture coordinates have v up; they are returned as (u, 1 - v) so that (0, 0) is
    the top-left texel (glTF's and Mitsuba's convention);
  * a face with no material, or an unknown one, gets the default material (Lambert 0.5).
Unindexed output (three vertices per triangle) keeps flat and smooth triangles apart without
any vertex splitting logic.
"""

from __future__ import annotations

import dataclasses
import os

import numpy as np


@dataclasses.dataclass
class ObjMaterial:
    name: str
    kd: tuple = (0.0, 0.0, 0.0)  # tinyobjloader's defaults, which geocold-cl reads MTL with
    ks: tuple = (0.0, 0.0, 0.0)
    ke: tuple = (0.0, 0.0, 0.0)
    ni: float = 1.0
    illum: int = 0
    map_kd: str | None = None  # absolute path of the diffuse texture
    # glTF metallic-roughness (make_reference.py --pbr; written by gltf_to_obj.py as the
    # PBR-MTL keys Pm / Pr, plus map_Pmr for glTF's packed texture and norm for the normal map)
    pbr: bool = False
    metallic: float = 0.0
    roughness: float = 1.0
    map_mr: str | None = None  # glTF metallicRoughness texture: B = metal, G = roughness (linear)
    map_norm: str | None = None  # tangent-space normal map (linear)
    # glTF dielectrics and metals (gltf_to_obj.py's Ptr, Pabs, Pmetal, Pgr, map_Pgr keys): the
    # transmission's index of refraction, its volume's absorption coefficients (None: no volume),
    # whether it is a metal, and the roughnessFactor, times the G of map_gltf_mr where given
    transmission_ior: float | None = None
    absorption: tuple | None = None
    metal: bool = False
    gltf_roughness: float = 0.0
    map_gltf_mr: str | None = None


DEFAULT_MATERIAL = ObjMaterial(name="<default>", kd=(0.5, 0.5, 0.5), illum=0)


@dataclasses.dataclass
class TriangleGroup:
    material: ObjMaterial
    positions: np.ndarray  # (3 * n, 3) float32
    normals: np.ndarray  # (3 * n, 3) float32
    uvs: np.ndarray | None  # (3 * n, 2) float32, or None when no triangle of the group has uvs


def _floats(tokens, count, where):
    try:
        values = [float(t) for t in tokens[:count]]
    except ValueError as e:
        raise ValueError(f"{where}: bad number: {e}") from None
    if len(values) < count:
        raise ValueError(f"{where}: expected {count} numbers")
    return tuple(values)


def read_mtl(path: str, materials: dict[str, ObjMaterial]) -> None:
    current = None
    base = os.path.dirname(path)
    with open(path, encoding="utf-8", errors="replace") as f:
        for line_no, raw in enumerate(f, 1):
            line = raw.split("#", 1)[0].strip()
            if not line:
                continue
            key, *rest = line.split()
            where = f"{path}:{line_no}"
            if key == "newmtl":
                current = ObjMaterial(name=" ".join(rest))
                materials[current.name] = current
            elif current is None:
                continue
            elif key == "Kd":
                current.kd = _floats(rest, 3, where)
            elif key == "Ks":
                current.ks = _floats(rest, 3, where)
            elif key == "Ke":
                current.ke = _floats(rest, 3, where)
            elif key == "Ni":
                current.ni = _floats(rest, 1, where)[0]
            elif key == "illum":
                current.illum = int(float(rest[0]))
            elif key == "Pm":
                current.pbr, current.metallic = True, _floats(rest, 1, where)[0]
            elif key == "Pr":
                current.pbr, current.roughness = True, _floats(rest, 1, where)[0]
            elif key == "Ptr":
                current.transmission_ior = _floats(rest, 1, where)[0]
            elif key == "Pmetal":
                current.metal = True
            elif key == "Pgr":
                current.gltf_roughness = _floats(rest, 1, where)[0]
            elif key == "map_Pgr" and rest:
                current.map_gltf_mr = os.path.normpath(os.path.join(base, rest[-1]))
            elif key == "Pabs":
                current.absorption = _floats(rest, 3, where)
            elif key == "map_Pmr" and rest:
                current.map_mr = os.path.normpath(os.path.join(base, rest[-1]))
            elif key == "norm" and rest:
                current.map_norm = os.path.normpath(os.path.join(base, rest[-1]))
            elif key == "map_Kd" and rest:
                # Options (-bm, -s, ...) are not supported: the file name is the last token.
                current.map_kd = os.path.normpath(os.path.join(base, rest[-1]))


def _index(token: str, count: int, where: str) -> int:
    i = int(token)
    i = i - 1 if i > 0 else count + i
    if not 0 <= i < count:
        raise ValueError(f"{where}: index {token} out of range")
    return i


def read_obj(path: str) -> list[TriangleGroup]:
    """All triangles of the file, grouped by material, in first-use order."""
    base = os.path.dirname(path)
    v, vn, vt = [], [], []
    materials: dict[str, ObjMaterial] = {}
    current = DEFAULT_MATERIAL
    # material name -> lists of (corner positions, corner normals or None, corner uvs or None)
    faces: dict[str, tuple[ObjMaterial, list]] = {}
    with open(path, encoding="utf-8", errors="replace") as f:
        for line_no, raw in enumerate(f, 1):
            line = raw.split("#", 1)[0].strip()
            if not line:
                continue
            key, *rest = line.split()
            where = f"{path}:{line_no}"
            if key == "v":
                v.append(_floats(rest, 3, where))
            elif key == "vn":
                vn.append(_floats(rest, 3, where))
            elif key == "vt":
                vt.append(_floats(rest, 2, where) if len(rest) >= 2 else (_floats(rest, 1, where)[0], 0.0))
            elif key == "mtllib":
                for name in rest:
                    lib = os.path.join(base, name)
                    if os.path.exists(lib):
                        read_mtl(lib, materials)
                    else:
                        print(f"warning: {where}: material library {name} not found")
            elif key == "usemtl":
                current = materials.get(" ".join(rest), DEFAULT_MATERIAL)
            elif key == "f":
                corners = []
                for token in rest:
                    parts = token.split("/")
                    pi = _index(parts[0], len(v), where)
                    ti = _index(parts[1], len(vt), where) if len(parts) > 1 and parts[1] else None
                    ni = _index(parts[2], len(vn), where) if len(parts) > 2 and parts[2] else None
                    corners.append((pi, ti, ni))
                entry = faces.setdefault(current.name, (current, []))
                for k in range(1, len(corners) - 1):
                    entry[1].append((corners[0], corners[k], corners[k + 1]))
    groups = []
    pos_all = np.asarray(v, dtype=np.float64).reshape(-1, 3)
    for material, tris in faces.values():
        if not tris:
            continue
        idx = np.array([[c[0] for c in t] for t in tris])
        p = pos_all[idx]  # (n, 3, 3)
        face_n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        length = np.linalg.norm(face_n, axis=1, keepdims=True)
        face_n = np.where(length > 0, face_n / np.maximum(length, 1e-300), np.array([0.0, 0.0, 1.0]))
        n = np.repeat(face_n[:, None, :], 3, axis=1)
        uv = np.zeros((len(tris), 3, 2))
        any_uv = False
        for i, t in enumerate(tris):
            if all(c[2] is not None for c in t):
                n[i] = [vn[c[2]] for c in t]
            if all(c[1] is not None for c in t):
                uv[i] = [(vt[c[1]][0], 1.0 - vt[c[1]][1]) for c in t]
                any_uv = True
        groups.append(
            TriangleGroup(
                material=material,
                positions=p.reshape(-1, 3).astype(np.float32),
                normals=n.reshape(-1, 3).astype(np.float32),
                uvs=uv.reshape(-1, 2).astype(np.float32) if any_uv else None,
            )
        )
    if not groups:
        raise ValueError(f"{path}: no faces")
    return groups
