"""geocold: the geocold-cl path tracer from Python.

Load a scene, render it on any OpenCL device (GPUs, or CPUs through PoCL) and get numpy
arrays back; edit materials and the camera between renders without reloading anything::

    import geocold as gc
    scene = gc.load("scene.glb")
    r = gc.Renderer(scene, device="any", integrator="path", res=(512, 512), max_depth=8, seed=0)
    img = r.render(spp=64)            # float32 (H, W, 4), linear RGB, row 0 = top
    img = r.render(spp=64)            # continues: 128 spp, the same bits as one 128-spp call
    scene.materials["red"].base_color = (0.8, 0.1, 0.1)   # the next render sees it
    gc.write("out.exr", img, metadata={"spp": 128})

The same scene and settings give the same bits as the ``geocold-cl`` command line.
"""

from __future__ import annotations

import os as _os
from dataclasses import dataclass as _dataclass
from pathlib import Path as _Path
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

from . import _geocold

__all__ = [
    "Error", "SceneError", "DeviceError", "OutputError", "ArgumentError",
    "Device", "devices", "load", "Scene", "Material", "Materials", "Camera", "Params",
    "Renderer", "Sums", "render_frame", "write", "read", "denoise", "INTEGRATORS", "AOVS", "__version__",
]
__version__ = "0.1.0"

Error = _geocold.Error
SceneError = _geocold.SceneError
DeviceError = _geocold.DeviceError
OutputError = _geocold.OutputError
ArgumentError = _geocold.ArgumentError

#: Every integrator the command line has (``--integrator``).
INTEGRATORS = ("path", "whitted", "aov")
#: Every AOV the command line has (``--aov``).
AOVS = ("preview", "albedo", "normal", "depth", "primid", "guide-albedo", "guide-normal")
#: Every sampler the command line has (``--sampler``).
SAMPLERS = ("independent", "sobol")

_HERE = _Path(__file__).resolve().parent
_IMAGE_MODULE = _HERE / "geocold-image-oiio.so"
_geocold._configure(str(_HERE / "kernels"),
                    "" if _os.environ.get("GEOCOLD_IMAGE_MODULE") or not _IMAGE_MODULE.exists()
                    else str(_IMAGE_MODULE))

Vec3 = Tuple[float, float, float]


@_dataclass(frozen=True)
class Device:
    """An OpenCL device, as ``geocold-cl --list-devices`` lists it.

    ``index`` is what ``Renderer(device=...)`` and the CLI's ``--device`` accept;
    ``kind`` is ``"gpu"``, ``"cpu"`` or ``"other"``.
    """

    index: int
    kind: str
    name: str
    platform: str
    vendor: str
    driver: str
    compute_units: int
    global_memory: int


def devices() -> list[Device]:
    """Every OpenCL device with a compiler, in the order ``--device <index>`` counts in.

    An empty list when there is no OpenCL platform or device."""
    return [Device(**d) for d in _geocold.devices()]


def _vec3(value: Any, what: str) -> Vec3:
    try:
        x, y, z = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ArgumentError(f"{what} must be three numbers, not {value!r}") from None
    return (x, y, z)


# The editable factors of a material, in one vocabulary for .obj/.mtl and glTF:
# base_color is Kd / baseColorFactor, emission Ke / emissiveFactor * strength, specular Ks,
# phong_exponent Ns, ior Ni, opacity d / baseColor alpha.
_MATERIAL_FIELDS = ("type", "base_color", "specular", "emission", "phong_exponent", "ior", "opacity",
                    "metallic", "roughness", "transmission", "normal_scale", "alpha_cutoff",
                    "double_sided")
_VEC3_FIELDS = ("base_color", "specular", "emission")
_CAMERA_FIELDS = ("look_from", "look_at", "up", "fov", "aperture", "focus_distance")


class Material:
    """One material of a scene, with its editable factors as attributes.

    Assigning one (``m.base_color = (0.8, 0.1, 0.1)``) changes the scene: every renderer of it
    sees the change at its next render, which restarts its film. No reload, no BVH build, and
    no program build unless the edit changes what the kernels must handle (a new material
    type, say). Factors: ``type`` (lambert, phong, mirror, dielectric, pbr), ``base_color``,
    ``specular``, ``emission`` (RGB tuples), ``phong_exponent``, ``ior``, ``opacity``,
    ``metallic``, ``roughness``, ``transmission``, ``normal_scale``, ``alpha_cutoff``,
    ``double_sided``. Bad values raise :class:`ArgumentError`.
    """

    __slots__ = ("_scene", "_index")

    def __init__(self, scene: "Scene", index: int):
        object.__setattr__(self, "_scene", scene)
        object.__setattr__(self, "_index", index)

    @property
    def name(self) -> str:
        """The material's name in the file."""
        return self._scene._core.material(self._index)["name"]

    @property
    def index(self) -> int:
        """The material's index in the scene."""
        return self._index

    def fields(self) -> Dict[str, Any]:
        """Every editable factor and its value."""
        d = self._scene._core.material(self._index)
        return {k: d[k] for k in _MATERIAL_FIELDS}

    def __getattr__(self, field: str) -> Any:
        if field in _MATERIAL_FIELDS:
            return self._scene._core.material(self._index)[field]
        raise AttributeError(f"Material has no attribute {field!r}")

    def __setattr__(self, field: str, value: Any) -> None:
        if field not in _MATERIAL_FIELDS:
            raise AttributeError(f"Material has no editable factor {field!r} "
                                 f"(editable: {', '.join(_MATERIAL_FIELDS)})")
        if field in _VEC3_FIELDS:
            value = _vec3(value, f"materials/{self.name}/{field}")
        elif field not in ("type", "double_sided"):
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise ArgumentError(f"materials/{self.name}/{field} must be a number, not {value!r}") from None
        self._scene._core.set_material(self._index, field, value)

    def __repr__(self) -> str:
        f = self.fields()
        return (f"Material({self.name!r}, type={f['type']!r}, base_color={f['base_color']}, "
                f"emission={f['emission']}, roughness={f['roughness']:g}, metallic={f['metallic']:g})")


class Materials(Mapping[str, Material]):
    """The scene's materials by name, in the file's order (``scene.materials["red"]``).

    A name that several materials share maps to the first; ``scene.materials.at(i)`` reaches
    every one by index."""

    def __init__(self, scene: "Scene"):
        self._scene = scene
        self._names = [scene._core.material(i)["name"] for i in range(scene._core.material_count())]

    def __getitem__(self, name: str) -> Material:
        try:
            return Material(self._scene, self._names.index(name))
        except ValueError:
            raise KeyError(f"{self._scene.path}: no material named {name!r} "
                           f"(materials: {', '.join(self._names)})") from None

    def at(self, index: int) -> Material:
        """The material at ``index`` in the file's order."""
        if not 0 <= index < len(self._names):
            raise IndexError(f"material index {index} out of range ({len(self._names)} materials)")
        return Material(self._scene, index)

    def __iter__(self) -> Iterator[str]:
        seen = set()
        for n in self._names:
            if n not in seen:
                seen.add(n)
                yield n

    def __len__(self) -> int:
        return len(set(self._names))

    def __repr__(self) -> str:
        return f"Materials({list(self)})"


class Camera:
    """The scene's camera: ``look_from``, ``look_at``, ``up``, ``fov`` (full vertical field of
    view, degrees), and a thin lens: ``aperture`` (the lens radius in scene units; 0, the
    default, is a pinhole) and ``focus_distance`` (along the view axis; 0 focuses on
    ``look_at``), as the CLI's ``--aperture`` and ``--focus-distance``. The file's camera, or
    the CLI's framing of the scene when it has none.

    Assignments take effect at every renderer's next render (its film restarts). A camera the
    CLI would refuse (look_from == look_at, up along the view, fov outside (0, 180), a negative
    aperture or focus distance) raises :class:`ArgumentError`."""

    __slots__ = ("_scene",)

    def __init__(self, scene: "Scene"):
        object.__setattr__(self, "_scene", scene)

    def _get(self) -> Dict[str, Any]:
        return self._scene._core.camera()

    def _apply(self, c: Dict[str, Any]) -> None:
        self._scene._core.set_camera(c["look_from"], c["look_at"], c["up"], c["fov"], c["aperture"],
                                     c["focus_distance"])

    def __getattr__(self, field: str) -> Any:
        if field in _CAMERA_FIELDS:
            return self._get()[field]
        raise AttributeError(f"Camera has no attribute {field!r}")

    def __setattr__(self, field: str, value: Any) -> None:
        if field not in _CAMERA_FIELDS:
            raise AttributeError(f"Camera has no editable attribute {field!r}")
        self.set(**{field: value})

    def set(self, look_from: Optional[Vec3] = None, look_at: Optional[Vec3] = None,
            up: Optional[Vec3] = None, fov: Optional[float] = None, aperture: Optional[float] = None,
            focus_distance: Optional[float] = None) -> None:
        """Changes several fields at once (checked together)."""
        c = self._get()
        for field, value in (("look_from", look_from), ("look_at", look_at), ("up", up)):
            if value is not None:
                c[field] = _vec3(value, f"camera/{field}")
        for field, value in (("fov", fov), ("aperture", aperture), ("focus_distance", focus_distance)):
            if value is not None:
                try:
                    c[field] = float(value)
                except (TypeError, ValueError):
                    raise ArgumentError(f"camera/{field} must be a number, not {value!r}") from None
        self._apply(c)

    def __repr__(self) -> str:
        c = self._get()
        return (f"Camera(look_from={c['look_from']}, look_at={c['look_at']}, up={c['up']}, fov={c['fov']:g}, "
                f"aperture={c['aperture']:g}, focus_distance={c['focus_distance']:g})")


class Params(Mapping[str, Any]):
    """Everything editable in the scene as one flat name -> value view, Mitsuba style:
    ``"materials/<name>/base_color"``, ``"materials/<name>/roughness"``, ...,
    ``"camera/look_from"``, ``"camera/look_at"``, ``"camera/up"``, ``"camera/fov"``,
    ``"camera/aperture"``, ``"camera/focus_distance"``, and the texels of the textures that can be
    differentiated, ``"textures/<i>/texels"`` ((h, w, 4) float32, linear; once set, the texture
    is stored as linear floats).

    ``params[key] = value`` edits the scene as the attribute would; ``params.update({...})``
    sets several. :meth:`differentiable` lists what :meth:`Renderer.backward` can
    differentiate, with shapes."""

    def __init__(self, scene: "Scene"):
        self._scene = scene

    def keys(self):  # type: ignore[override]
        return list(iter(self))

    def __iter__(self) -> Iterator[str]:
        for name in self._scene.materials:
            for f in _MATERIAL_FIELDS:
                yield f"materials/{name}/{f}"
        for f in _CAMERA_FIELDS:
            yield f"camera/{f}"
        yield from self._texel_keys()

    def __len__(self) -> int:
        return len(self._scene.materials) * len(_MATERIAL_FIELDS) + len(_CAMERA_FIELDS) + len(self._texel_keys())

    def differentiable(self) -> Dict[str, Tuple[int, ...]]:
        """Every parameter :meth:`Renderer.backward` differentiates, name -> shape:
        ``materials/<m>/base_color`` (3), ``emission`` (3, materials that emit), ``specular``
        (3), ``phong_exponent`` (1), ``metallic`` (1), ``roughness`` (1);
        ``environment/radiance`` (3, the renderer's environment); ``textures/<i>/texels``
        (h, w, 4). ``<m>`` is the material's name where unique, else its index. Geometry, the
        camera and indices of refraction are not differentiable."""
        return {name: tuple(shape) for name, shape in self._scene._core.param_shapes()}

    def _texel_keys(self) -> List[str]:
        return [name for name, _ in self._scene._core.param_shapes() if name.startswith("textures/")]

    @staticmethod
    def _texture_index(key: str) -> Optional[int]:
        parts = key.split("/")
        if len(parts) == 3 and parts[0] == "textures" and parts[2] == "texels" and parts[1].isdigit():
            return int(parts[1])
        return None

    def _target(self, key: str) -> Tuple[Any, str]:
        parts = key.split("/")
        if len(parts) == 2 and parts[0] == "camera" and parts[1] in _CAMERA_FIELDS:
            return self._scene.camera, parts[1]
        if len(parts) >= 3 and parts[0] == "materials" and parts[-1] in _MATERIAL_FIELDS:
            name = "/".join(parts[1:-1])
            if name in self._scene.materials:
                return self._scene.materials[name], parts[-1]
        raise KeyError(f"{self._scene.path}: no parameter {key!r}")

    def __getitem__(self, key: str) -> Any:
        index = self._texture_index(key)
        if index is not None:
            return self._scene._core.texels(index)
        obj, field = self._target(key)
        return getattr(obj, field)

    def __setitem__(self, key: str, value: Any) -> None:
        index = self._texture_index(key)
        if index is not None:
            import numpy as np
            self._scene._core.set_texels(index, np.ascontiguousarray(value, dtype=np.float32))
            return
        obj, field = self._target(key)
        setattr(obj, field, value)

    def update(self, values: Mapping[str, Any] = (), **kwargs: Any) -> None:  # type: ignore[override]
        """Sets every key of ``values``."""
        for k, v in dict(values, **kwargs).items():
            self[k] = v

    def __repr__(self) -> str:
        def short(k: str) -> str:
            return f"array{tuple(self[k].shape)}" if self._texture_index(k) is not None else repr(self[k])
        return "Params({" + ", ".join(f"{k!r}: {short(k)}" for k in self) + "})"


class Scene:
    """A scene loaded by :func:`load`: geometry and BVH on the host, editable materials and
    camera. Renderers made from it share it; edits reach them at their next render."""

    def __init__(self, core: Any):
        self._core = core
        self._materials = Materials(self)
        self._camera = Camera(self)
        self._params = Params(self)

    @property
    def path(self) -> str:
        """The file the scene came from."""
        return self._core.path

    @property
    def materials(self) -> Materials:
        """Every material by name, with its editable factors."""
        return self._materials

    @property
    def camera(self) -> Camera:
        """The scene's camera (editable)."""
        return self._camera

    @camera.setter
    def camera(self, other: "Camera") -> None:
        self._camera.set(other.look_from, other.look_at, other.up, other.fov)

    @property
    def params(self) -> Params:
        """Everything editable as a flat name -> value view."""
        return self._params

    @property
    def triangle_count(self) -> int:
        """Triangles in the scene."""
        return self._core.triangle_count()

    @property
    def timings(self) -> Dict[str, float]:
        """Seconds spent loading the file and building the BVH."""
        return {"load": self._core.load_seconds, "bvh": self._core.bvh_seconds}

    def __repr__(self) -> str:
        return f"Scene({self.path!r}, {self.triangle_count} triangles, {len(self.materials)} materials)"


def load(path: Union[str, "_os.PathLike[str]"], *, gltf_scene: int = -1,
         look_from: Optional[Vec3] = None, look_at: Optional[Vec3] = None,
         up: Optional[Vec3] = None, fov: Optional[float] = None, aperture: Optional[float] = None,
         focus_distance: Optional[float] = None) -> Scene:
    """Loads a ``.obj``/``.mtl``, ``.gltf`` or ``.glb`` file and builds its BVH.

    The camera is the file's, or framed on the scene as the CLI frames it; ``look_from``,
    ``look_at``, ``up``, ``fov``, ``aperture`` and ``focus_distance`` override it like
    ``--look-from`` etc. (:class:`Camera`). ``gltf_scene``
    picks a glTF scene (-1: the file's default). Raises :class:`SceneError` naming the file
    on bad input."""
    path = _os.fspath(path)
    if not isinstance(path, str):
        raise ArgumentError(f"load: path must be a str or os.PathLike, not {type(path).__name__}")
    scene = Scene(_geocold.load(path, int(gltf_scene)))
    if any(v is not None for v in (look_from, look_at, up, fov, aperture, focus_distance)):
        scene.camera.set(look_from, look_at, up, fov, aperture, focus_distance)
    return scene


@_dataclass(frozen=True)
class Sums:
    """A film's raw content (``Renderer.sums()``): per pixel, row 0 at the top, the sums of the
    samples' radiance (``sums``, (H, W, 4) float32; alpha: the sample count as float), of their
    squares (``squares``) and the sample counts (``sample_counts``, (H, W) uint32). Sums of
    renders of disjoint sample ranges add up."""

    sums: Any
    squares: Any
    sample_counts: Any


class Renderer:
    """A film and one integrator on one device, over a :class:`Scene`.

    ``device``: the CLI's ``--device`` specs (``"any"``, ``"gpu"``, ``"cpu"``, an index, part
    of a name) or a :class:`Device`. ``integrator``: ``"path"``, ``"whitted"`` or ``"aov"``;
    ``aov`` (implies ``integrator="aov"``): ``"preview"``, ``"albedo"``, ``"normal"``,
    ``"depth"``, ``"primid"``. ``res``: (width, height). ``spp``: the samples
    :meth:`render` adds by default (64; 1 for AOVs, as in the CLI). ``env``: a constant
    environment radiance, or the scale of ``env_map`` (a lat-long .exr/.hdr/.pfm).
    ``sampler``: ``"sobol"`` (the default: Owen-scrambled Sobol points, as the CLI) or
    ``"independent"`` (``--sampler independent``). ``samples_per_pass`` and
    ``wavefront_size`` change only the speed.

    Construction uploads the scene to the device and builds (or loads from the cache) the
    kernels. Raises :class:`DeviceError` for a device that does not exist,
    :class:`ArgumentError` for bad settings."""

    def __init__(self, scene: Scene, device: Union[str, int, Device] = "any", integrator: str = "path",
                 aov: Optional[str] = None, res: Tuple[int, int] = (512, 512), max_depth: int = 8,
                 seed: int = 0, spp: Optional[int] = None, rr_depth: int = 5,
                 env: Union[float, Vec3] = (0.0, 0.0, 0.0), env_map: Optional[str] = None,
                 samples_per_pass: int = 0, wavefront_size: int = 0, sampler: str = "sobol"):
        if not isinstance(scene, Scene):
            raise ArgumentError(f"Renderer: scene must be a geocold.Scene (from geocold.load), "
                                f"not {type(scene).__name__}")
        if isinstance(device, Device):
            device = str(device.index)
        elif isinstance(device, int) and not isinstance(device, bool):
            device = str(device)
        elif not isinstance(device, str):
            raise ArgumentError(f"Renderer: device must be a str, an int or a geocold.Device, not {device!r}")
        if aov is not None:
            integrator = "aov"
        if integrator not in INTEGRATORS:
            raise ArgumentError(f"Renderer: integrator must be one of {', '.join(INTEGRATORS)}, not {integrator!r}")
        aov = aov or "preview"
        if aov not in AOVS:
            raise ArgumentError(f"Renderer: aov must be one of {', '.join(AOVS)}, not {aov!r}")
        if sampler not in SAMPLERS:
            raise ArgumentError(f"Renderer: sampler must be one of {', '.join(SAMPLERS)}, not {sampler!r}")
        try:
            width, height = (int(v) for v in res)
        except (TypeError, ValueError):
            raise ArgumentError(f"Renderer: res must be (width, height), not {res!r}") from None
        if isinstance(env, (int, float)):
            env = (float(env),) * 3
        env = _vec3(env, "Renderer: env")
        if spp is None:
            spp = 1 if integrator == "aov" else 64
        for name, value, low in (("max_depth", max_depth, 1), ("seed", seed, 0), ("spp", spp, 0),
                                 ("rr_depth", rr_depth, 0), ("samples_per_pass", samples_per_pass, 0),
                                 ("wavefront_size", wavefront_size, 0)):
            if isinstance(value, bool) or not isinstance(value, int) or not low <= value < 2 ** 32:
                raise ArgumentError(f"Renderer: {name} must be an integer in [{low}, 2^32), not {value!r}")
        self._scene = scene
        self._core = _geocold.RendererCore(scene._core, device, integrator, aov, width, height, spp, seed, sampler,
                                           max_depth, rr_depth, env, env_map or "", samples_per_pass,
                                           wavefront_size)
        self._spp = spp
        self._integrator = integrator if integrator != "aov" else f"aov:{aov}"

    @property
    def scene(self) -> Scene:
        """The scene this renderer renders."""
        return self._scene

    def render(self, spp: Optional[int] = None, *, time_limit: Optional[float] = None,
               progress: Optional[Callable[[int, int], Any]] = None) -> Any:
        """Adds ``spp`` samples per pixel (default: the constructor's ``spp``) to the film and
        returns its mean: a new float32 numpy array (H, W, 4), linear RGB, alpha 1, row 0 at
        the top. Calls continue one another: two 64-spp calls give the same bits as one
        128-spp call. After a scene edit the film restarts.

        ``time_limit`` (seconds) stops after the pass that reaches it; ``progress(done,
        target)`` is called after each pass with the film's sample count. Ctrl-C raises
        ``KeyboardInterrupt`` at the next pass boundary with the film intact (``film()``,
        ``sample_count``). The GIL is released while the device works."""
        if spp is None:
            spp = self._spp
        if isinstance(spp, bool) or not isinstance(spp, int) or not 0 <= spp < 2 ** 32:
            raise ArgumentError(f"render: spp must be a non-negative integer, not {spp!r}")
        if time_limit is None:
            time_limit = 0.0
        try:
            time_limit = float(time_limit)
        except (TypeError, ValueError):
            raise ArgumentError(f"render: time_limit must be seconds, not {time_limit!r}") from None
        if progress is not None and not callable(progress):
            raise ArgumentError("render: progress must be callable")
        return self._core.render(spp, time_limit, progress)

    def film(self) -> Any:
        """The film's mean so far, as :meth:`render` returns it."""
        return self._core.film()

    def variance(self) -> Any:
        """Per-pixel sample variance (unbiased) so far, (H, W, 4) float32; path integrator only."""
        return self._core.variance()

    def sums(self) -> Sums:
        """The film's per-pixel sums, squares and sample counts (:class:`Sums`)."""
        return Sums(*self._core.sums())

    def clear(self) -> None:
        """Empties the film; the next render starts again at sample 0."""
        self._core.clear()

    @property
    def sample_count(self) -> int:
        """Samples each pixel of the film holds (0 after a scene edit until the next render)."""
        return self._core.sample_count

    @property
    def info(self) -> Dict[str, Any]:
        """The device, the settings, and the set-up's timings: ``load_seconds``,
        ``bvh_seconds``, ``upload_seconds``, ``compile_seconds`` (0 when the program came
        from the cache: ``program_from_cache``), ``program_builds`` (programs rebuilt since
        construction, by edits that changed the kernel features), ``render_seconds``."""
        return self._core.info()

    def backward(self, loss_grad: Any, params: Sequence[str], spp: int = 4, seed: int = 1) -> Dict[str, Any]:
        """Gradients of a loss of this renderer's image with respect to scene parameters
        (:meth:`Params.differentiable`), by path replay backpropagation on the renderer's device.

        ``loss_grad``: d loss / d image, (H, W, 3 or 4) (alpha ignored), e.g.
        ``2 * (img[..., :3] - target[..., :3]) / img[..., :3].size`` for the MSE. ``spp`` samples
        per pixel with ``seed``: use a seed other than the image's for an unbiased gradient.
        Returns name -> float32 array in the parameter's shape. The sums are exact integers,
        so the same call gives the same bits every time on a device. Path integrator only;
        an unknown or non-differentiable name raises :class:`ArgumentError` saying why."""
        import numpy as np

        names = [params] if isinstance(params, str) else [str(p) for p in params]
        grad = np.ascontiguousarray(loss_grad, dtype=np.float32)
        flat = self._core.backward(grad, names, int(spp), int(seed))
        shapes = self._scene.params.differentiable()
        return {name: flat[name].reshape(shapes.get(name, flat[name].shape)) for name in names}

    def metadata(self) -> Dict[str, Any]:
        """The metadata :func:`write` records for this renderer's film."""
        i = self._core.info()
        return {"device": i["device"], "integrator": self._integrator, "scene": self._scene.path,
                "spp": self.sample_count, "seconds": i["render_seconds"], "seed": i["seed"]}

    def __repr__(self) -> str:
        i = self._core.info()
        return (f"Renderer({self._scene.path!r}, {self._integrator}, {i['width']}x{i['height']}, "
                f"{self.sample_count} spp, {i['device']!r})")


def render_frame(scene: Scene, devices: Union[str, list] = "all", spp: int = 64, *,
                 samples: Optional[Tuple[int, int]] = None, chunk_samples: int = 64,
                 integrator: str = "path", aov: Optional[str] = None, res: Tuple[int, int] = (512, 512),
                 max_depth: int = 8, seed: int = 0, rr_depth: int = 5,
                 env: Union[float, Vec3] = (0.0, 0.0, 0.0), env_map: Optional[str] = None,
                 time_limit: float = 0.0, noise_threshold: float = 0.0,
                 sampler: str = "sobol") -> Tuple[Any, int]:
    """Renders one frame on several devices at once, as ``geocold-cl --device all``.

    ``devices``: ``"all"``, or a list of device specs (as :class:`Renderer`'s ``device``). The
    frame is cut into chunks of ``chunk_samples`` samples that the devices pull; the chunks
    are added in chunk order, so devices of one kind give the bits of one device, and of the
    CLI with the same ``--chunk-samples``. ``samples=(a, b)``: only samples [a, b) (``a`` a
    multiple of ``chunk_samples``), like ``--samples a:b``. Returns ``(image, spp)``: the mean
    (float32 (H, W, 4)) and the samples per pixel in it (fewer than asked when ``time_limit``
    ended the frame). ``noise_threshold=T`` (> 0), like ``--noise-threshold T``: adaptive
    sampling, each 8x8 tile stopping once its pixels' relative standard error is below ``T``,
    ``spp`` the cap; the same image on every run. ``sampler`` as :class:`Renderer`'s. Ctrl-C
    raises ``KeyboardInterrupt``."""
    if not isinstance(scene, Scene):
        raise ArgumentError(f"render_frame: scene must be a geocold.Scene, not {type(scene).__name__}")
    if isinstance(devices, str):
        specs = [devices]
    else:
        specs = [str(d.index) if isinstance(d, Device) else str(d) for d in devices]
    if aov is not None:
        integrator = "aov"
    if integrator not in INTEGRATORS:
        raise ArgumentError(f"render_frame: integrator must be one of {', '.join(INTEGRATORS)}, not {integrator!r}")
    aov = aov or "preview"
    if aov not in AOVS:
        raise ArgumentError(f"render_frame: aov must be one of {', '.join(AOVS)}, not {aov!r}")
    if sampler not in SAMPLERS:
        raise ArgumentError(f"render_frame: sampler must be one of {', '.join(SAMPLERS)}, not {sampler!r}")
    try:
        width, height = (int(v) for v in res)
    except (TypeError, ValueError):
        raise ArgumentError(f"render_frame: res must be (width, height), not {res!r}") from None
    if isinstance(env, (int, float)):
        env = (float(env),) * 3
    env = _vec3(env, "render_frame: env")
    first, end = (0, spp) if samples is None else samples
    for name, value, low in (("spp", end, 1), ("chunk_samples", chunk_samples, 1), ("max_depth", max_depth, 1),
                             ("seed", seed, 0), ("rr_depth", rr_depth, 0), ("first sample", first, 0)):
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value < 2 ** 32:
            raise ArgumentError(f"render_frame: {name} must be an integer in [{low}, 2^32), not {value!r}")
    if isinstance(noise_threshold, bool) or not isinstance(noise_threshold, (int, float)):
        raise ArgumentError(f"render_frame: noise_threshold must be a number, not {noise_threshold!r}")
    return _geocold.render_frame(scene._core, specs, integrator, aov, width, height, first, end, chunk_samples,
                                 seed, sampler, max_depth, rr_depth, env, env_map or "", float(time_limit),
                                 float(noise_threshold))


_META_KEYS = ("device", "integrator", "scene", "spp", "seconds", "seed")


def write(path: Union[str, "_os.PathLike[str]"], image: Any,
          metadata: Optional[Mapping[str, Any]] = None, *, tonemap: str = "pbr-neutral",
          exposure: float = 0.0) -> None:
    """Writes an (H, W, 3 or 4) image (linear RGB, row 0 = top) to ``path``, atomically, as the
    CLI writes: ``.exr`` (float RGBA with ``geocold:*`` metadata), ``.png`` (sRGB 8 bit),
    ``.pfm``, ``.ppm``, and the other formats OpenImageIO writes. ``metadata`` keys:
    ``device``, ``integrator``, ``scene``, ``spp``, ``seconds``, ``seed`` (a
    :meth:`Renderer.metadata` dict fits). 8-bit formats go through the display transform
    ``tonemap`` after ``exposure`` stops: ``"pbr-neutral"`` (the default, as the CLI's for a
    rendered image), ``"clamp"`` (a clip at 1: what the CLI writes for an AOV, so pass it for
    albedos and other data), ``"agx"``, ``"aces"``, ``"none"``. Float formats stay linear.
    Raises :class:`OutputError` naming the file."""
    import numpy as np

    meta = dict(metadata or {})
    unknown = set(meta) - set(_META_KEYS)
    if unknown:
        raise ArgumentError(f"write: unknown metadata {', '.join(sorted(unknown))} "
                            f"(known: {', '.join(_META_KEYS)})")
    arr = np.ascontiguousarray(image, dtype=np.float32)
    if arr.ndim == 2:
        arr = np.ascontiguousarray(np.repeat(arr[:, :, None], 3, axis=2))
    if arr.ndim != 3 or arr.shape[2] not in (3, 4):
        raise ArgumentError(f"write: the image must be (height, width, 3 or 4), not {arr.shape}")
    try:
        _geocold.write(_os.fspath(path), arr, str(meta.get("device", "")), str(meta.get("integrator", "")),
                       str(meta.get("scene", "")), int(meta.get("spp", 0)), float(meta.get("seconds", 0.0)),
                       int(meta.get("seed", 0)), str(tonemap), float(exposure))
    except (TypeError, OverflowError) as e:
        raise ArgumentError(f"write: bad metadata: {e}") from None


def denoise(color: Any, albedo: Any = None, normal: Any = None, *, clean_aux: bool = False) -> Any:
    """Denoises a linear HDR image (H, W, 3 or 4) with Intel Open Image Denoise's ``RT``
    filter on the CPU, through PyPI's ``pyoidn`` (``pip install pyoidn``), and returns a
    float32 image of the same shape (alpha kept). ``albedo`` and ``normal`` are optional
    guides of the same size, e.g. ``Renderer(scene, aov="albedo")`` and ``aov="normal"``
    renders (``normal`` needs ``albedo``); ``clean_aux=True`` says they are noise-free (rendered
    with enough samples), as the CLI's ``--denoise`` guides are. Raises :class:`DeviceError`
    without ``pyoidn`` and :class:`ArgumentError` on mismatched shapes."""
    import numpy as np

    try:
        import pyoidn
    except ImportError as e:
        raise DeviceError(f"denoise needs the pyoidn package (pip install pyoidn): {e}") from None

    def rgb(image: Any, what: str) -> Any:
        arr = np.asarray(image, dtype=np.float32)
        if arr.ndim != 3 or arr.shape[2] not in (3, 4):
            raise ArgumentError(f"denoise: {what} must be (height, width, 3 or 4), not {arr.shape}")
        return np.ascontiguousarray(arr[..., :3])

    c = rgb(color, "color")
    guides = {}
    for name, image in (("albedo", albedo), ("normal", normal)):
        if image is not None:
            guides[name] = rgb(image, name)
            if guides[name].shape != c.shape:
                raise ArgumentError(f"denoise: {name} is {guides[name].shape[:2]}, color {c.shape[:2]}")
    if "normal" in guides and "albedo" not in guides:
        raise ArgumentError("denoise: a normal guide needs an albedo guide too (OIDN's rule)")
    out = np.asarray(pyoidn.denoise(c, guides.get("albedo"), guides.get("normal"), hdr=True,
                                    clean_aux=bool(clean_aux and guides)), dtype=np.float32)
    arr = np.asarray(color, dtype=np.float32)
    if arr.shape[2] == 4:
        out = np.concatenate([out, arr[..., 3:]], axis=2)
    return out


def read(path: Union[str, "_os.PathLike[str]"]) -> Any:
    """Reads an image file (EXR, PNG, PFM, PPM, HDR, TIFF, ...) as float32 (H, W, 4), linear
    RGB (8-bit files are decoded from sRGB), alpha 1 where the file has none. Raises
    :class:`SceneError` naming the file when it cannot be read."""
    return _geocold.read(_os.fspath(path))
