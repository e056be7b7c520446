"""Turns triangle groups (obj_scene.py) and a view into a Mitsuba 3 scene.

The material mapping is the conventions table of /work/shared/refs/README.md:
  illum 0-2 (and 10)  Lambert with Kd (times map_Kd when present); Ks/Ns ignored
  illum 3, 5 (and 8)  Kd/pi diffuse PLUS a perfect mirror of reflectance Ks (no Fresnel)
  illum 4, 6, 7 (9)   smooth dielectric, interior IOR Ni, exterior 1.0
  Ke != 0             one-sided area light of radiance Ke on top of the surface's BSDF
  non-dielectrics     two-sided
(illum 8, 9, 10 are not in the table; they follow geocold-cl's OBJ loader.)

glTF transmission (gltf_to_obj.py's Ptr, Pabs, Pgr, map_Pgr): rough, a GGX
`roughdielectric` of its IOR (alpha = roughness^2, at least geocold-cl's 1e-3) whose
transmittance is the base colour; smooth with a volume (Pabs given), a `dielectric` likewise;
either over a `homogeneous` purely absorbing interior medium when the volume attenuates (the scene then
renders with `volpathmis`); smooth and thin-walled, glTF's delta pair at normal incidence: a
blend of a mirror of weight F0 = ((ior - 1) / (ior + 1))^2 and a pass-through tinted by the
base colour (a `thindielectric` of IOR 1); at IOR 1, rough or not, that pass-through alone.
Mitsuba's Fresnel is exact where glTF's is Schlick's: they agree at normal incidence. A glTF
metal (Pmetal) becomes a GGX `roughconductor` reflecting the base colour (`metal_bsdf`).

Mitsuba 3 has no additive BSDF, so the diffuse + mirror sum is a blendbsdf with weight w:
    (1 - w) * diffuse(Kd / (1 - w)) + w * conductor(Ks / w) = Kd/pi + delta * Ks
with `conductor` of material "none" (reflectance exactly 1, i.e. no Fresnel). w is the mirror's
share of the luminance, lum(Ks) / (lum(Kd) + lum(Ks)), kept inside [max Ks, 1 - max Kd] so
that neither scaled lobe exceeds 1 where that is possible. w only changes which lobe Mitsuba
samples (the variance), not the BSDF.
"""

from __future__ import annotations

import mitsuba as mi
import numpy as np

from colour import luminance
from obj_scene import TriangleGroup

LAMBERT_ILLUM = {0, 1, 2, 10}
MIRROR_ILLUM = {3, 5, 8}
DIELECTRIC_ILLUM = {4, 6, 7, 9}


def _rgb(c) -> dict:
    return {"type": "rgb", "value": [float(x) for x in c]}


def _float_bitmap(data: np.ndarray) -> dict:
    # Texels already linear (raw: no sRGB decoding), filtered and wrapped as geocold-cl's.
    return {"type": "bitmap", "bitmap": mi.Bitmap(np.ascontiguousarray(data, dtype=np.float32)), "raw": True,
            "filter_type": "bilinear", "wrap_mode": "repeat"}


def _diffuse_reflectance(material, scale: float = 1.0) -> dict:
    kd = np.asarray(material.kd, dtype=np.float64) * scale
    if material.map_kd is None:
        return _rgb(kd)
    if np.allclose(kd, 1.0):
        return {"type": "bitmap", "filename": material.map_kd, "filter_type": "bilinear", "wrap_mode": "repeat"}
    # Kd times the texture: Mitsuba has no product texture, so bake Kd into a linear copy.
    bitmap = mi.Bitmap(material.map_kd).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    return _float_bitmap(np.array(bitmap) * kd.astype(np.float32))


def _data_texels(path: str) -> np.ndarray:
    """An image's stored values as floats (H, W, 3). Mitsuba takes an 8-bit image for sRGB and
    would decode it on conversion; glTF's data textures (metallicRoughness) hold linear values."""
    bitmap = mi.Bitmap(path)
    bitmap.set_srgb_gamma(False)
    return np.array(bitmap.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False))


def _channel_texture(path: str, channel: int, factor: float) -> dict:
    # One linear channel of an image (glTF packs metallic in B and roughness in G), times the
    # factor, as a float bitmap texture.
    return _float_bitmap(_data_texels(path)[:, :, channel:channel + 1] * np.float32(factor))


def principled_bsdf(material) -> dict:
    """glTF metallic-roughness as Mitsuba's principled BSDF (make_reference.py --pbr).

    base_color = baseColorFactor x texture, metallic = factor x B, roughness = factor x G,
    specular 0.5 (Mitsuba maps it to eta 1.5, i.e. F0 0.04 as glTF), normal map through
    `normalmap`, two-sided like every non-dielectric here. Convention differences that remain
    (README.md): principled's diffuse is Disney's (retro-reflection grows with roughness) and not
    weighted by 1 - F; its dielectric Fresnel is exact, not Schlick's.
    """
    bsdf = {"type": "principled", "base_color": _diffuse_reflectance(material), "specular": 0.5,
            "metallic": float(material.metallic), "roughness": float(material.roughness)}
    if material.map_mr is not None:
        bsdf["metallic"] = _channel_texture(material.map_mr, 2, material.metallic)
        bsdf["roughness"] = _channel_texture(material.map_mr, 1, material.roughness)
    if material.map_norm is not None:
        bsdf = {"type": "normalmap", "bsdf": bsdf,
                "normalmap": {"type": "bitmap", "filename": material.map_norm, "raw": True,
                              "filter_type": "bilinear", "wrap_mode": "repeat"}}
    return {"type": "twosided", "bsdf": bsdf}


def absorbs(material) -> bool:
    """Whether the material has an interior medium that absorbs."""
    return material.absorption is not None and max(material.absorption) > 0.0


MIN_ALPHA = 1e-3  # geocold-cl's GC_PBR_MIN_ALPHA: a smoother facet is taken as this rough


def _metallic_is(material, metallic: float) -> bool:
    """Whether a glTF material's metallic is `metallic` everywhere: its metallicRoughness
    texture's B, where it has one (gltf_to_obj.py checked the factor)."""
    if material.map_gltf_mr is None:
        return True
    return np.abs(_data_texels(material.map_gltf_mr)[:, :, 2] - metallic).max() <= 1.0 / 255.0


def _gltf_alpha(material):
    """GGX alpha = roughness^2 (at least MIN_ALPHA), a float or a bitmap texture; None if smooth."""
    if material.gltf_roughness <= 0.0:
        return None
    if material.map_gltf_mr is None:
        return max(material.gltf_roughness ** 2, MIN_ALPHA)
    texels = _data_texels(material.map_gltf_mr)
    return _float_bitmap(np.maximum((texels[:, :, 1:2] * np.float32(material.gltf_roughness)) ** 2, MIN_ALPHA))


def transmission_bsdf(material) -> dict:
    tint = _rgb(material.kd)
    alpha = _gltf_alpha(material)
    if material.transmission_ior == 1.0:
        # Facets of an IOR of 1 bend no light whatever their slopes (geocold-cl's
        # gc_pbr_transmission_alpha): a pass-through tinted by the base colour.
        return {"type": "thindielectric", "int_ior": 1.0, "ext_ior": 1.0, "specular_transmittance": tint}
    if alpha is not None:
        return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha, "sample_visible": True,
                "int_ior": float(material.transmission_ior), "ext_ior": 1.0, "specular_transmittance": tint}
    if material.absorption is not None:
        return {"type": "dielectric", "int_ior": float(material.transmission_ior), "ext_ior": 1.0,
                "specular_transmittance": tint}
    f0 = ((material.transmission_ior - 1.0) / (material.transmission_ior + 1.0)) ** 2
    return {"type": "blendbsdf", "weight": float(f0),
            "bsdf_0": {"type": "thindielectric", "int_ior": 1.0, "ext_ior": 1.0, "specular_transmittance": tint},
            "bsdf_1": {"type": "conductor", "material": "none"}}


def metal_bsdf(material) -> dict:
    """glTF's metal: GGX facets reflecting the base colour (Mitsuba's conductor of material
    "none" reflects its specular_reflectance at every angle, glTF's rises to white at grazing
    angles by Schlick's law: they agree at normal incidence)."""
    alpha = _gltf_alpha(material)
    bsdf = {"type": "conductor" if alpha is None else "roughconductor", "material": "none",
            "specular_reflectance": _diffuse_reflectance(material)}
    if alpha is not None:
        bsdf.update({"distribution": "ggx", "alpha": alpha, "sample_visible": True})
    return {"type": "twosided", "bsdf": bsdf}


def material_bsdf(material) -> dict:
    if material.transmission_ior is not None or material.metal:
        if _metallic_is(material, 0.0 if material.transmission_ior is not None else 1.0):
            return transmission_bsdf(material) if material.transmission_ior is not None else metal_bsdf(material)
        print(f"warning: material {material.name}: its texture's metallic varies; rendered as Lambert baseColor")
    if material.pbr:
        return principled_bsdf(material)
    if material.illum in DIELECTRIC_ILLUM:
        return {"type": "dielectric", "int_ior": float(material.ni), "ext_ior": 1.0}
    kd = np.asarray(material.kd, dtype=np.float64)
    ks = np.asarray(material.ks, dtype=np.float64)
    if material.illum in MIRROR_ILLUM and ks.max() > 0:
        mirror = {"type": "conductor", "material": "none"}
        if kd.max() <= 0 and material.map_kd is None:
            bsdf = dict(mirror, specular_reflectance=_rgb(ks))
        else:
            lum_d, lum_s = luminance(kd), luminance(ks)
            w = lum_s / (lum_d + lum_s) if lum_d + lum_s > 0 else 0.5
            lo, hi = ks.max(), 1.0 - kd.max()
            if lo <= hi:
                w = min(max(w, lo), hi)
            w = min(max(w, 1e-4), 1.0 - 1e-4)
            bsdf = {
                "type": "blendbsdf",
                "weight": float(w),
                "bsdf_0": {"type": "diffuse", "reflectance": _diffuse_reflectance(material, 1.0 / (1.0 - w))},
                "bsdf_1": dict(mirror, specular_reflectance=_rgb(ks / w)),
            }
    else:
        if material.illum not in LAMBERT_ILLUM and material.illum not in MIRROR_ILLUM:
            print(f"warning: material {material.name}: illum {material.illum} not supported; using Lambert")
        bsdf = {"type": "diffuse", "reflectance": _diffuse_reflectance(material)}
    return {"type": "twosided", "bsdf": bsdf}


def float_texture_storage(bsdf):
    """The BSDF dict with its image textures stored as the variant's floats. Mitsuba 3.9 keeps
    an 8-bit image as uint8 texels (sRGB decoded at each lookup), a tensor without gradients;
    format "variant" decodes it to linear floats once, the values geocold differentiates."""
    if isinstance(bsdf, dict):
        if bsdf.get("type") == "bitmap" and "filename" in bsdf:
            bsdf = dict(bsdf, format="variant")
        return {k: float_texture_storage(v) for k, v in bsdf.items()}
    return bsdf


def group_mesh(name: str, group: TriangleGroup, float_textures: bool = False) -> mi.Mesh:
    props = mi.Properties()
    bsdf = material_bsdf(group.material)
    props["bsdf"] = mi.load_dict(float_texture_storage(bsdf) if float_textures else bsdf)
    if absorbs(group.material):
        # An RGB value here is read as a reflectance (at most 1): the largest coefficient goes
        # into the medium's scale.
        sigma = np.asarray(group.material.absorption, dtype=np.float64)
        largest = max(float(sigma.max()), 1e-30)
        props["interior"] = mi.load_dict({"type": "homogeneous", "sigma_t": _rgb(sigma / largest), "scale": largest,
                                          "albedo": _rgb((0.0, 0.0, 0.0))})
    if max(group.material.ke) > 0:
        # Mitsuba's area light is one-sided: it emits on the side the triangle's normal
        # (counter-clockwise winding) faces, as the convention asks.
        props["emitter"] = mi.load_dict({"type": "area", "radiance": _rgb(group.material.ke)})
    n_vertices = len(group.positions)
    mesh = mi.Mesh(name, n_vertices, n_vertices // 3, props, True, group.uvs is not None)
    params = mi.traverse(mesh)

    def put(key, array):
        params[key] = type(params[key])(np.ascontiguousarray(array).ravel())

    put("vertex_positions", group.positions.astype(np.float32))
    put("faces", np.arange(n_vertices, dtype=np.uint32))
    put("vertex_normals", group.normals.astype(np.float32))
    if group.uvs is not None:
        put("vertex_texcoords", group.uvs.astype(np.float32))
    params.update()
    return mesh


def integrator_for(groups, integrator: str = "path") -> str:
    """The integrator build_scene renders these groups with, asked for `integrator`."""
    if integrator == "path" and any(absorbs(g.material) for g in groups):
        # The same estimator with the media the path integrator ignores; volpathmis weighs the
        # distance sampling of the three channels by MIS (volpath samples one channel's distance,
        # so a colour absorbed at very different rates gets fireflies in the others).
        return "volpathmis"
    return integrator


def build_scene(groups, camera: dict, max_depth: int, env, seed: int = 0, integrator: str = "path",
                float_textures: bool = False) -> mi.Scene:
    width, height = camera["res"]
    integrator = integrator_for(groups, integrator)
    scene = {
        "type": "scene",
        "integrator": {"type": integrator, "max_depth": int(max_depth)},
        "sensor": {
            # Mitsuba's thinlens: the plane in focus at focus_distance along the view axis, as
            # geocold-cl's gc_camera_sample.
            **({"type": "thinlens", "aperture_radius": float(camera["aperture_radius"]),
                "focus_distance": float(camera["focus_distance"])}
               if camera.get("aperture_radius", 0) > 0 else {"type": "perspective"}),
            "fov": float(camera["fov"]),
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=camera["look_from"], target=camera["look_at"], up=camera.get("up", [0.0, 1.0, 0.0])
            ),
            "sampler": {"type": "independent", "seed": int(seed)},
            "film": {
                "type": "hdrfilm",
                "width": int(width),
                "height": int(height),
                "pixel_format": "rgb",
                "rfilter": {"type": "box"},
            },
        },
    }
    if env is not None and max(env) > 0:
        scene["environment"] = {"type": "constant", "radiance": _rgb(env)}
    for i, group in enumerate(groups):
        scene[f"mesh_{i:03d}"] = group_mesh(f"mesh_{i:03d}_{group.material.name}", group, float_textures)
    return mi.load_dict(scene)
