#!/usr/bin/env python3
"""Writes the stress corpus: OBJ scenes (each with its own .mtl) that probe the promise
"same image on every device, at every scale" where floating point is most fragile.

Every scene is derived from the Cornell boxes bundled in scenes/cornell-box (CC BY 3.0,
see scenes/cornell-box/README.md) or generated procedurally inside one, deterministically:
fixed seeds, coordinates rounded to float32 first and written with %.9g, so the file holds
exactly the floats the transform produced and every run writes the same bytes. The files
carry no camera: geocold-cl frames the scene bounds, so a transformed box gets the
transformed view. See tools/stress/README.md for what each scene probes.

Usage: make_corpus.py --out DIR [--only NAME ...]   writes DIR/<name>.obj and DIR/<name>.mtl
       make_corpus.py --list                        prints the scene names, one a line
"""

import argparse
import array
import hashlib
import math
import os
import random
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
BOXES = os.path.join(ROOT, "scenes", "cornell-box")
# Bumped when the output changes for a reason the stamp cannot see (it hashes this file and
# the source scenes, so edits to either regenerate anyway).
FORMAT = 1

WALLS = ("floor", "ceiling", "backWall", "rightWall", "leftWall")


def f32(values):
    """Rounds doubles to float32, so %.9g writes exactly the float the renderer will load."""
    return array.array("f", values).tolist()


def fmt3(tag, x, y, z):
    return "%s %.9g %.9g %.9g\n" % (tag, x, y, z)


# ---------------------------------------------------------------------------------------
# Small vector and transform helpers (doubles; rounding to float happens once, on write).

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def lerp(a, b, t):
    return add(a, mul(sub(b, a), t))


def rotation(axis, degrees):
    """Rodrigues' rotation matrix (rows) about a unit axis."""
    x, y, z = normalize(axis)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    t = 1.0 - c
    return ((t * x * x + c, t * x * y - s * z, t * x * z + s * y),
            (t * x * y + s * z, t * y * y + c, t * y * z - s * x),
            (t * x * z - s * y, t * y * z + s * x, t * z * z + c))


def apply(m, v):
    return (dot(m[0], v), dot(m[1], v), dot(m[2], v))


class Similarity:
    """p -> scale * R p + offset. Normals only rotate (a similarity keeps angles)."""

    def __init__(self, scale=1.0, offset=(0.0, 0.0, 0.0), rot=None):
        self.scale, self.offset, self.rot = scale, offset, rot

    def point(self, p):
        q = apply(self.rot, p) if self.rot else p
        return add(mul(q, self.scale), self.offset)

    def normal(self, n):
        return normalize(apply(self.rot, n)) if self.rot else n


# ---------------------------------------------------------------------------------------
# Reading the bundled boxes.

def read_lines(path):
    with open(path, "r", encoding="utf-8") as f:
        return [line.rstrip("\r\n") for line in f]


def floats(line):
    return tuple(float(x) for x in line.split()[1:4])


def polygons(obj_path):
    """The faces of an OBJ with only `v` and `f` records (the Original/Mirror boxes):
    [(material, [corner positions])], negative and positive indices resolved."""
    verts, faces, material = [], [], None
    for line in read_lines(obj_path):
        word = line.split("#", 1)[0].split()
        if not word:
            continue
        if word[0] == "v":
            verts.append(tuple(float(x) for x in word[1:4]))
        elif word[0] == "usemtl":
            material = word[1]
        elif word[0] == "f":
            idx = [int(c.split("/")[0]) for c in word[1:]]
            faces.append((material, [verts[i - 1] if i > 0 else verts[len(verts) + i] for i in idx]))
    return faces


def licence_header(source):
    return ("# Derived from scenes/cornell-box/%s by tools/stress/make_corpus.py.\n"
            "# Cornell box: Guedis Cardenas, Morgan McGuire, Michael Mara (Williams College, 2011),\n"
            "# CC BY 3.0 (scenes/cornell-box/copyright.txt).\n" % source)


def mtl_text(source_mtl, extra=""):
    body = "\n".join(read_lines(os.path.join(BOXES, source_mtl)))
    return licence_header(source_mtl) + "\n" + body + "\n" + extra


# ---------------------------------------------------------------------------------------
# Writing.

class ObjWriter:
    """OBJ writer with absolute indices: vertices() and normals() return the 1-based index
    of the first entry they wrote."""

    def __init__(self, path, name, header):
        self.f = open(path, "w", encoding="utf-8", newline="\n")
        self.f.write(header)
        self.f.write("mtllib %s.mtl\n" % name)
        self.nv = self.nvn = 0

    def vertices(self, pts):
        flat = f32([c for p in pts for c in p])
        self.f.write("".join(fmt3("v", *flat[i:i + 3]) for i in range(0, len(flat), 3)))
        base, self.nv = self.nv + 1, self.nv + len(pts)
        return base

    def normals(self, ns):
        flat = f32([c for n in ns for c in n])
        self.f.write("".join(fmt3("vn", *flat[i:i + 3]) for i in range(0, len(flat), 3)))
        base, self.nvn = self.nvn + 1, self.nvn + len(ns)
        return base

    def group(self, name, material):
        self.f.write("g %s\nusemtl %s\n" % (name, material))

    def faces(self, faces, normal_faces=None):
        """faces: index tuples (absolute); normal_faces: the `vn` index per corner, or None."""
        if normal_faces is None:
            self.f.write("".join("f " + " ".join(str(i) for i in face) + "\n" for face in faces))
        else:
            self.f.write("".join("f " + " ".join("%d//%d" % c for c in zip(face, nf)) + "\n"
                                 for face, nf in zip(faces, normal_faces)))

    def polygon(self, pts):
        base = self.vertices(pts)
        self.faces([tuple(range(base, base + len(pts)))])

    def close(self):
        self.f.close()


def write_mtl(out, name, text):
    with open(os.path.join(out, name + ".mtl"), "w", encoding="utf-8", newline="\n") as f:
        f.write(text)


# ---------------------------------------------------------------------------------------
# Scenes that transform a bundled box: every `v` and `vn` goes through the transform, every
# other record is kept as it is (negative face indices stay valid: no vertex is added).

def transformed(source, xf, what):
    def build(out, name):
        src = "CornellBox-%s" % source
        with open(os.path.join(out, name + ".obj"), "w", encoding="utf-8", newline="\n") as f:
            f.write(licence_header(src + ".obj"))
            f.write("# %s\n" % what)
            for line in read_lines(os.path.join(BOXES, src + ".obj")):
                word = line.split()
                if word and word[0] == "v":
                    f.write(fmt3("v", *f32(xf.point(floats(line)))))
                elif word and word[0] == "vn":
                    f.write(fmt3("vn", *f32(xf.normal(floats(line)))))
                elif word and word[0] == "mtllib":
                    f.write("mtllib %s.mtl\n" % name)
                else:
                    f.write(line + "\n")
        write_mtl(out, name, mtl_text(src + ".mtl"))
    return build


# ---------------------------------------------------------------------------------------
# Long thin slivers: each wall of the Original box (a quad) becomes 1000 strips across it,
# two triangles each, so every triangle is ~2 units long and ~0.002 wide (aspect ~1000:1).
# The strips share their vertices; the wall's outline and winding are kept.

SLIVER_STRIPS = 1000


def slivers(out, name):
    w = ObjWriter(os.path.join(out, name + ".obj"), name,
                  licence_header("CornellBox-Original.obj") +
                  "# walls re-tessellated into %d strips of two triangles each (aspect ~%d:1)\n"
                  % (SLIVER_STRIPS, SLIVER_STRIPS))
    for k, (material, pts) in enumerate(polygons(os.path.join(BOXES, "CornellBox-Original.obj"))):
        if material not in WALLS:
            w.group("%s_%d" % (material, k), material)
            w.polygon(pts)
            continue
        c0, c1, c2, c3 = pts
        n = SLIVER_STRIPS
        # Bilinear in the quad: a = the c0-c1 edge, b = the c3-c2 edge, strips run from a to b.
        a = [lerp(c0, c1, i / n) for i in range(n + 1)]
        b = [lerp(c3, c2, i / n) for i in range(n + 1)]
        base = w.vertices(a + b)
        tris = []
        for i in range(n):
            ai, aj, bi, bj = base + i, base + i + 1, base + n + 1 + i, base + n + 2 + i
            tris += [(ai, aj, bj), (ai, bj, bi)]
        w.group("%s_slivers" % material, material)
        w.faces(tris)
    w.close()
    write_mtl(out, name, mtl_text("CornellBox-Original.mtl"))


# ---------------------------------------------------------------------------------------
# Coincident and overlapping faces. The source box already repeats one face of each block;
# here every wall is repeated too (same corners, separate vertices, same material), and
# quads of other materials lie in the planes of the back wall, the floor and the two
# blocks' front faces. Which face is hit is decided by the rounding of t and, on exact ties,
# by the tie rule (the smaller triangle index wins): both must come out the same everywhere.
# Quads written before the box win exact ties, those after it lose them; in the blocks'
# oblique planes the quads' corners round differently from the face's, so t differs by
# rounding and the two faces interleave (z-fighting) in a pattern every device must share.

OVERLAP_MTL = """
newmtl overlapBlue
Ns 10.0000
Ni 1.0000
illum 2
Kd 0.1 0.2 0.7
Ks 0 0 0

newmtl overlapYellow
Ns 10.0000
Ni 1.0000
illum 2
Kd 0.7 0.6 0.1
Ks 0 0 0
"""


def inset(quad, u0, u1, v0, v1):
    """The part [u0, u1] x [v0, v1] of a planar quad, by bilinear interpolation (coplanar in
    exact arithmetic; each corner rounds to float on its own)."""
    c0, c1, c2, c3 = quad

    def at(u, v):
        return lerp(lerp(c0, c1, u), lerp(c3, c2, u), v)
    return [at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1)]


def coincident(out, name):
    w = ObjWriter(os.path.join(out, name + ".obj"), name,
                  licence_header("CornellBox-Original.obj") +
                  "# every wall duplicated; coplanar overlapping quads on the back wall, the floor\n"
                  "# and the blocks' front faces\n")
    faces = polygons(os.path.join(BOXES, "CornellBox-Original.obj"))
    # Before the box: these win exact ties. The back wall is the plane z = -1.04 and the
    # floor y = 0 in the source file; the floor's quad is wound the other way (normal down).
    w.group("overlapBack", "overlapBlue")
    w.polygon([(-0.6, 0.3, -1.04), (0.4, 0.3, -1.04), (0.4, 1.5, -1.04), (-0.6, 1.5, -1.04)])
    w.group("overlapFloorReversed", "overlapBlue")
    w.polygon([(-0.2, 0.0, 0.5), (-0.2, 0.0, -0.6), (0.5, 0.0, -0.6), (0.5, 0.0, 0.5)])
    for k, (material, pts) in enumerate(faces):
        w.group("%s_%d" % (material, k), material)
        w.polygon(pts)
    for material, pts in faces:
        if material in WALLS:
            w.group("%s_copy" % material, material)
            w.polygon(pts)
    # After the box: these lose exact ties.
    w.group("overlapFloor", "overlapYellow")
    w.polygon([(-0.7, 0.0, 0.8), (0.8, 0.0, 0.8), (0.8, 0.0, -0.3), (-0.7, 0.0, -0.3)])
    tall_front = [(0.04, 0.0, -0.09), (0.04, 1.2, -0.09), (-0.53, 1.2, 0.09), (-0.53, 0.0, 0.09)]
    short_front = [(0.53, 0.0, 0.75), (0.53, 0.6, 0.75), (-0.05, 0.6, 0.57), (-0.05, 0.0, 0.57)]
    assert all(any(pts == q for _, pts in faces) for q in (tall_front, short_front))
    w.group("overlapTall", "overlapBlue")
    w.polygon(inset(tall_front, 0.15, 0.85, 0.2, 0.8))
    w.group("overlapShort", "overlapYellow")
    w.polygon(inset(short_front, 0.1, 0.9, 0.1, 0.9))
    w.close()
    write_mtl(out, name, mtl_text("CornellBox-Original.mtl", OVERLAP_MTL))


# ---------------------------------------------------------------------------------------
# Smooth procedural meshes with vertex normals, in the Original box's walls and light.

def uv_sphere(center, radius, n_lon, n_lat, bump=None):
    """Vertices, outward unit normals and outward-wound triangles (0-based) of a sphere;
    bump(theta, phi) scales the radius (normals are then left to the caller)."""
    pts, nrm = [], []
    for j in range(1, n_lat):
        theta = math.pi * j / n_lat
        st, ct = math.sin(theta), math.cos(theta)
        for i in range(n_lon):
            phi = 2.0 * math.pi * i / n_lon
            d = (st * math.cos(phi), ct, st * math.sin(phi))
            r = radius * (bump(theta, phi) if bump else 1.0)
            pts.append(add(center, mul(d, r)))
            nrm.append(d)
    north, south = len(pts), len(pts) + 1
    pts += [add(center, (0.0, radius * (bump(0.0, 0.0) if bump else 1.0), 0.0)),
            add(center, (0.0, -radius * (bump(math.pi, 0.0) if bump else 1.0), 0.0))]
    nrm += [(0.0, 1.0, 0.0), (0.0, -1.0, 0.0)]
    tris = []

    def at(j, i):  # ring j in 0..n_lat-2 (theta grows with j), longitude i wraps
        return j * n_lon + i % n_lon

    # Wound so that cross(b - a, c - a) points outward (phi grows toward -x/+z on a ring).
    for i in range(n_lon):
        tris.append((north, at(0, i + 1), at(0, i)))
        tris.append((south, at(n_lat - 2, i), at(n_lat - 2, i + 1)))
    for j in range(n_lat - 2):
        for i in range(n_lon):
            a, b, c, d = at(j, i), at(j, i + 1), at(j + 1, i + 1), at(j + 1, i)
            tris += [(a, b, c), (a, c, d)]
    return pts, nrm, tris


def torus(center, major, minor, n_major, n_minor, rot):
    pts, nrm, tris = [], [], []
    for i in range(n_major):
        u = 2.0 * math.pi * i / n_major
        ring = (math.cos(u), 0.0, math.sin(u))
        for j in range(n_minor):
            v = 2.0 * math.pi * j / n_minor
            d = add(mul(ring, math.cos(v)), (0.0, math.sin(v), 0.0))
            pts.append(add(center, apply(rot, add(mul(ring, major), mul(d, minor)))))
            nrm.append(apply(rot, d))
    for i in range(n_major):
        for j in range(n_minor):
            a = i * n_minor + j
            b = ((i + 1) % n_major) * n_minor + j
            c = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor
            d = i * n_minor + (j + 1) % n_minor
            tris += [(a, d, c), (a, c, b)]
    return pts, nrm, tris


CURVED_MTL = """
newmtl glossyTorus
Ns 60
Ni 1.0000
illum 2
Kd 0.45 0.42 0.40
Ks 0.35 0.35 0.35

newmtl mirrorSphere
Kd 0.01 0.01 0.01
Ks 0.95 0.95 0.95
Ns 1000
illum 5

newmtl glassSphere
Kd 0.01 0.01 0.01
Ks 0.30 0.30 0.30
Tf 0.90 0.90 0.90
Ns 200
Ni 1.5
illum 7
"""


def curved_objects():
    """(group, material, points, normals, triangles) for a torus and two spheres that sit
    apart from each other and from the walls."""
    return [
        ("torus", "glossyTorus") + torus((-0.4, 0.5, -0.3), 0.32, 0.13, 48, 24,
                                          rotation((1.0, 0.0, 0.35), 55.0)),
        ("mirrorSphere", "mirrorSphere") + uv_sphere((0.45, 0.33, 0.25), 0.32, 40, 20),
        ("glassSphere", "glassSphere") + uv_sphere((0.45, 0.95, -0.5), 0.25, 32, 16),
    ]


def box_walls_and_light(w):
    for k, (material, pts) in enumerate(polygons(os.path.join(BOXES, "CornellBox-Original.obj"))):
        if material in WALLS or material == "light":
            w.group("%s_%d" % (material, k), material)
            w.polygon(pts)


def perturb(n, max_degrees, rng):
    """n turned by an angle uniform in [0, max_degrees] about a random axis normal to it."""
    helper = (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)
    t = normalize(cross(n, helper))
    b = cross(n, t)
    phi = 2.0 * math.pi * rng.random()
    axis = add(mul(t, math.cos(phi)), mul(b, math.sin(phi)))
    return normalize(apply(rotation(axis, max_degrees * rng.random()), n))


def normals_flipped(out, name):
    w = ObjWriter(os.path.join(out, name + ".obj"), name,
                  licence_header("CornellBox-Original.obj") +
                  "# a torus and two spheres whose vertex normals all point inward (against the winding)\n")
    box_walls_and_light(w)
    for group, material, pts, nrm, tris in curved_objects():
        base, nbase = w.vertices(pts), w.normals([mul(n, -1.0) for n in nrm])
        w.group(group, material)
        w.faces([tuple(base + i for i in t) for t in tris], [tuple(nbase + i for i in t) for t in tris])
    w.close()
    write_mtl(out, name, mtl_text("CornellBox-Original.mtl", CURVED_MTL))


BENT_DEGREES = 80.0
BENT_AWAY_FRACTION = 0.125


def normals_bent(out, name):
    rng = random.Random(39)
    w = ObjWriter(os.path.join(out, name + ".obj"), name,
                  licence_header("CornellBox-Original.obj") +
                  "# a torus and two spheres: vertex normals turned by up to %g degrees; on %g %% of\n"
                  "# the triangles the corners' normals are negated, so the interpolated normal faces\n"
                  "# away from the winding\n" % (BENT_DEGREES, 100 * BENT_AWAY_FRACTION))
    box_walls_and_light(w)
    for group, material, pts, nrm, tris in curved_objects():
        bent = [perturb(n, BENT_DEGREES, rng) for n in nrm]
        base, nbase = w.vertices(pts), w.normals(bent)
        away = [k for k in range(len(tris)) if rng.random() < BENT_AWAY_FRACTION]
        abase = w.normals([mul(bent[i], -1.0) for k in away for i in tris[k]])
        corner_normals = [tuple(nbase + i for i in t) for t in tris]
        for m, k in enumerate(away):
            corner_normals[k] = (abase + 3 * m, abase + 3 * m + 1, abase + 3 * m + 2)
        w.group(group, material)
        w.faces([tuple(base + i for i in t) for t in tris], corner_normals)
    w.close()
    write_mtl(out, name, mtl_text("CornellBox-Original.mtl", CURVED_MTL))


# ---------------------------------------------------------------------------------------
# One big mesh: a displaced sphere of 1,046,528 triangles (faceted, no `vn`, to keep the
# file near 45 MB) in the Original box's walls and light. Its edges are ~600 times shorter
# than the walls', so the BVH is deep and spawn offsets come from tiny triangles.

BIG_LON, BIG_LAT = 1024, 512

BIG_MTL = """
newmtl displaced
Ns 30
Ni 1.0000
illum 2
Kd 0.60 0.58 0.55
Ks 0.15 0.15 0.15
"""


def mesh_1m(out, name):
    def bump(theta, phi):
        return (1.0 + 0.06 * math.sin(13.0 * theta) * math.cos(11.0 * phi)
                + 0.02 * math.sin(47.0 * theta + 3.0 * phi) * math.sin(41.0 * phi))

    pts, _, tris = uv_sphere((0.0, 0.72, -0.1), 0.55, BIG_LON, BIG_LAT, bump)
    w = ObjWriter(os.path.join(out, name + ".obj"), name,
                  licence_header("CornellBox-Original.obj") +
                  "# a displaced sphere of %d triangles\n" % len(tris))
    box_walls_and_light(w)
    base = w.vertices(pts)
    w.group("displacedSphere", "displaced")
    w.faces([(a + base, b + base, c + base) for a, b, c in tris])
    w.close()
    write_mtl(out, name, mtl_text("CornellBox-Original.mtl", BIG_MTL))


# ---------------------------------------------------------------------------------------

OBLIQUE = rotation((0.4, 0.5, 1.0), 25.0)  # no wall stays parallel to a coordinate plane


def corpus():
    """name -> builder(out_dir, name), in the order the tests are declared."""
    scenes = {}
    for source in ("Original", "Sphere"):
        for label, s in (("1e-3", 1e-3), ("1", 1.0), ("1e3", 1e3), ("1e4", 1e4)):
            scenes["%s-scale-%s" % (source.lower(), label)] = transformed(
                source, Similarity(scale=s), "uniform scale %g" % s)
    for label, s, offset in (("translate-1e3", 1.0, (1e3, -3e2, 7e2)),
                             ("translate-1e5", 1.0, (1e5, -3e4, 7e4)),
                             ("scale-1e2-translate-1e3", 1e2, (1e3, -3e2, 7e2)),
                             ("scale-1e3-translate-1e5", 1e3, (1e5, -3e4, 7e4)),
                             # the floor stays at y = 0 while the camera is ~1350 away: a
                             # surface on a coordinate plane far from the camera
                             ("scale-5e2-translate-8e2", 5e2, (8e2, 0.0, -6e2))):
        scenes["original-" + label] = transformed(
            "Original", Similarity(scale=s, offset=offset),
            "uniform scale %g, then translation by (%g, %g, %g)" % ((s,) + offset))
    scenes["sphere-scale-1e3-translate-1e5"] = transformed(
        "Sphere", Similarity(scale=1e3, offset=(1e5, -3e4, 7e4)),
        "uniform scale 1000, then translation by (1e5, -3e4, 7e4)")
    for source in ("Original", "Sphere"):
        scenes["%s-rotate-oblique" % source.lower()] = transformed(
            source, Similarity(rot=OBLIQUE), "rotation by 25 degrees about the axis (0.4, 0.5, 1)")
    scenes["original-slivers"] = slivers
    scenes["original-coincident"] = coincident
    scenes["normals-flipped"] = normals_flipped
    scenes["normals-bent"] = normals_bent
    scenes["mesh-1m"] = mesh_1m
    return scenes


def fingerprint(names):
    """Hash of everything the output depends on: this script, the source boxes, the names."""
    h = hashlib.sha256(("format %d\n%s\n" % (FORMAT, " ".join(names))).encode())
    for path in [os.path.abspath(__file__)] + sorted(
            os.path.join(BOXES, f) for f in os.listdir(BOXES) if f.endswith((".obj", ".mtl"))):
        with open(path, "rb") as f:
            h.update(f.read())
    return h.hexdigest()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", help="output directory (created)")
    ap.add_argument("--list", action="store_true", help="print the scene names and exit")
    ap.add_argument("--only", nargs="+", metavar="NAME", help="write only these scenes")
    ap.add_argument("--force", action="store_true", help="rewrite even when the stamp says up to date")
    args = ap.parse_args()
    scenes = corpus()
    if args.list:
        print("\n".join(scenes))
        return 0
    if not args.out:
        ap.error("--out DIR is required")
    names = args.only or list(scenes)
    unknown = [n for n in names if n not in scenes]
    if unknown:
        ap.error("unknown scene(s): %s (see --list)" % ", ".join(unknown))
    os.makedirs(args.out, exist_ok=True)
    # The 1M-triangle mesh takes seconds to write; skip the work when nothing changed.
    stamp = os.path.join(args.out, "corpus.stamp")
    key = fingerprint(names)
    present = all(os.path.exists(os.path.join(args.out, n + ext)) for n in names for ext in (".obj", ".mtl"))
    if not args.force and present and os.path.exists(stamp):
        with open(stamp, encoding="utf-8") as f:
            if f.read().strip() == key:
                print("stress corpus: %d scenes up to date in %s" % (len(names), args.out))
                return 0
    if os.path.exists(stamp):
        os.remove(stamp)
    for n in names:
        scenes[n](args.out, n)
    with open(stamp, "w", encoding="utf-8") as f:
        f.write(key + "\n")
    print("stress corpus: wrote %d scenes to %s" % (len(names), args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
