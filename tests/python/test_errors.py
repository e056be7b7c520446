"""Bad files, devices and arguments raise the right geocold exception, naming the file."""

import numpy as np
import pytest

from conftest import CORNELL, RES, ROOT

BAD = ROOT / "tests" / "data" / "bad"


def test_hierarchy(gc):
    for e in (gc.SceneError, gc.DeviceError, gc.OutputError, gc.ArgumentError):
        assert issubclass(e, gc.Error)
    assert issubclass(gc.ArgumentError, ValueError)


def test_missing_and_bad_scene_files(gc, tmp_path):
    with pytest.raises(gc.SceneError, match="nowhere.obj"):
        gc.load(tmp_path / "nowhere.obj")
    bad = sorted(BAD.glob("*.glb"))[:3] + sorted(BAD.glob("*.obj"))[:3]
    assert bad
    for path in bad:
        with pytest.raises(gc.SceneError, match=path.name):
            gc.load(path)
    junk = tmp_path / "junk.gltf"
    junk.write_text("{ not json")
    with pytest.raises(gc.SceneError, match="junk.gltf"):
        gc.load(junk)


def test_bad_device(gc, cornell):
    with pytest.raises(gc.DeviceError, match="no-such-device-xyz"):
        gc.Renderer(cornell, device="no-such-device-xyz", res=RES)
    with pytest.raises(gc.DeviceError):
        gc.Renderer(cornell, device=999, res=RES)


def test_bad_arguments(gc, cornell, device):
    bad = [dict(integrator="nope"), dict(aov="nope"), dict(res=(0, 10)), dict(res="big"),
           dict(max_depth=0), dict(seed=-1), dict(spp=1.5), dict(env=(1, 2)), dict(device=3.5), dict(sampler="halton")]
    for kwargs in bad:
        with pytest.raises(gc.ArgumentError):
            gc.Renderer(cornell, **{"device": device, "res": RES, **kwargs})
    with pytest.raises(ValueError):
        gc.Renderer("not a scene")
    r = gc.Renderer(cornell, device=device, res=RES)
    with pytest.raises(ValueError):
        r.render(spp=-1)
    with pytest.raises(ValueError):
        r.render(time_limit=-1)
    m = cornell.materials["floor"]
    for field, value in (("base_color", (2, 0, 0)), ("base_color", (0.1, 0.2)), ("roughness", 1.5),
                         ("ior", 0), ("emission", (-1, 0, 0)), ("type", "velvet"), ("roughness", "x")):
        with pytest.raises(gc.ArgumentError, match="floor"):
            setattr(m, field, value)
    with pytest.raises(AttributeError):
        m.no_such_factor = 1


def test_bad_output_and_input_images(gc, tmp_path):
    img = np.zeros((4, 4, 4), np.float32)
    with pytest.raises(gc.OutputError, match="no-dir"):
        gc.write(tmp_path / "no-dir" / "out.exr", img)
    with pytest.raises(gc.OutputError, match="out.xyz"):
        gc.write(tmp_path / "out.xyz", img)
    with pytest.raises(gc.ArgumentError):
        gc.write(tmp_path / "out.pfm", np.zeros((4, 4, 2), np.float32))
    with pytest.raises(gc.ArgumentError):
        gc.write(tmp_path / "out.pfm", img, metadata={"colour": 1})
    with pytest.raises(gc.SceneError, match="missing.exr"):
        gc.read(tmp_path / "missing.exr")
    broken = tmp_path / "broken.png"
    broken.write_bytes(b"not a png")
    with pytest.raises(gc.SceneError, match="broken.png"):
        gc.read(broken)
