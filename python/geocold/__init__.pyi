"""geocold: the geocold-cl path tracer from Python (see __init__.py for the documentation)."""

import os
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._geocold import ArgumentError as ArgumentError
from ._geocold import DeviceError as DeviceError
from ._geocold import Error as Error
from ._geocold import OutputError as OutputError
from ._geocold import SceneError as SceneError

__version__: str
INTEGRATORS: Tuple[str, ...]
AOVS: Tuple[str, ...]
SAMPLERS: Tuple[str, ...]
Vec3 = Tuple[float, float, float]
Image = npt.NDArray[np.float32]
PathLike = Union[str, os.PathLike[str]]

class Device:
    """An OpenCL device, as ``geocold-cl --list-devices`` lists it."""
    index: int
    kind: str
    name: str
    platform: str
    vendor: str
    driver: str
    compute_units: int
    global_memory: int

def devices() -> list[Device]:
    """Every OpenCL device with a compiler, in the order ``--device <index>`` counts in."""

class Material:
    """One material of a scene; assigning a factor edits the scene for every renderer."""
    type: str
    base_color: Vec3
    specular: Vec3
    emission: Vec3
    phong_exponent: float
    ior: float
    opacity: float
    metallic: float
    roughness: float
    transmission: float
    normal_scale: float
    alpha_cutoff: float
    double_sided: bool
    @property
    def name(self) -> str: ...
    @property
    def index(self) -> int: ...
    def fields(self) -> Dict[str, Any]:
        """Every editable factor and its value."""

class Materials(Mapping[str, Material]):
    """The scene's materials by name, in the file's order."""
    def __getitem__(self, name: str) -> Material: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def at(self, index: int) -> Material:
        """The material at ``index`` in the file's order."""

class Camera:
    """The scene's camera (editable): look_from, look_at, up, fov (vertical, degrees), and a thin
    lens: aperture (lens radius; 0 = pinhole) and focus_distance (0 = to look_at)."""
    look_from: Vec3
    look_at: Vec3
    up: Vec3
    fov: float
    aperture: float
    focus_distance: float
    def set(self, look_from: Optional[Vec3] = ..., look_at: Optional[Vec3] = ..., up: Optional[Vec3] = ...,
            fov: Optional[float] = ..., aperture: Optional[float] = ...,
            focus_distance: Optional[float] = ...) -> None:
        """Changes several fields at once (checked together)."""

class Params(Mapping[str, Any]):
    """Everything editable as a flat view: "materials/<name>/<factor>", "camera/<field>",
    "textures/<i>/texels"."""
    def differentiable(self) -> Dict[str, Tuple[int, ...]]:
        """What Renderer.backward differentiates: name -> shape."""
    def __getitem__(self, key: str) -> Any: ...
    def __setitem__(self, key: str, value: Any) -> None: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def update(self, values: Mapping[str, Any] = ..., **kwargs: Any) -> None:
        """Sets every key of ``values``."""

class Scene:
    """A loaded scene: geometry and BVH on the host, editable materials and camera."""
    @property
    def path(self) -> str: ...
    @property
    def materials(self) -> Materials: ...
    @property
    def camera(self) -> Camera: ...
    @camera.setter
    def camera(self, other: Camera) -> None: ...
    @property
    def params(self) -> Params: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def timings(self) -> Dict[str, float]: ...

def load(path: PathLike, *, gltf_scene: int = ..., look_from: Optional[Vec3] = ..., look_at: Optional[Vec3] = ...,
         up: Optional[Vec3] = ..., fov: Optional[float] = ..., aperture: Optional[float] = ...,
         focus_distance: Optional[float] = ...) -> Scene:
    """Loads a .obj/.mtl, .gltf or .glb file and builds its BVH; SceneError naming the file on bad input."""

class Sums:
    """A film's per-pixel sums, squares and sample counts; sums of disjoint ranges add up."""
    sums: Image
    squares: Image
    sample_counts: npt.NDArray[np.uint32]

class Renderer:
    """A film and one integrator on one device, over a Scene."""
    def __init__(self, scene: Scene, device: Union[str, int, Device] = ..., integrator: str = ...,
                 aov: Optional[str] = ..., res: Tuple[int, int] = ..., max_depth: int = ..., seed: int = ...,
                 spp: Optional[int] = ..., rr_depth: int = ..., env: Union[float, Vec3] = ...,
                 env_map: Optional[str] = ..., samples_per_pass: int = ..., wavefront_size: int = ...,
                 sampler: str = ...) -> None: ...
    @property
    def scene(self) -> Scene: ...
    def render(self, spp: Optional[int] = ..., *, time_limit: Optional[float] = ...,
               progress: Optional[Callable[[int, int], Any]] = ...) -> Image:
        """Adds spp samples to the film (continuing it) and returns its mean, float32 (H, W, 4)."""
    def film(self) -> Image: ...
    def variance(self) -> Image: ...
    def sums(self) -> Sums: ...
    def clear(self) -> None: ...
    @property
    def sample_count(self) -> int: ...
    @property
    def info(self) -> Dict[str, Any]: ...
    def backward(self, loss_grad: Any, params: Sequence[str], spp: int = ..., seed: int = ...) -> Dict[str, Any]:
        """d loss / d parameter from d loss / d image, by path replay backpropagation; deterministic."""
    def metadata(self) -> Dict[str, Any]: ...

def render_frame(scene: Scene, devices: Union[str, List[Union[str, int, Device]]] = ..., spp: int = ..., *,
                 samples: Optional[Tuple[int, int]] = ..., chunk_samples: int = ..., integrator: str = ...,
                 aov: Optional[str] = ..., res: Tuple[int, int] = ..., max_depth: int = ..., seed: int = ...,
                 rr_depth: int = ..., env: Union[float, Vec3] = ..., env_map: Optional[str] = ...,
                 time_limit: float = ..., noise_threshold: float = ..., sampler: str = ...) -> Tuple[Image, int]:
    """One frame on several devices (chunks added in chunk order); returns (mean image, spp).
    noise_threshold > 0: adaptive sampling, spp the cap."""

def denoise(color: Any, albedo: Any = ..., normal: Any = ..., *, clean_aux: bool = ...) -> Any: ...
def write(path: PathLike, image: Any, metadata: Optional[Mapping[str, Any]] = ..., *, tonemap: str = ...,
          exposure: float = ...) -> None:
    """Writes an (H, W, 3 or 4) linear image atomically (.exr, .png, .pfm, .ppm, ...); OutputError naming the file."""

def read(path: PathLike) -> Image:
    """Reads an image file as float32 (H, W, 4), linear RGB; SceneError naming the file."""
