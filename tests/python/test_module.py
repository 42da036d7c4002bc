# The module's behaviour beyond the pictures: errors and their messages,
# Ctrl-C, a Scene outliving its file, threads rendering at once, the scene's
# views, info(), convert, write_image, the documentation.
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from conftest import COURSE, GLB, GLTF, OBJ, read_png, run_cli

SIZE = (64, 48)


def cli_error(*args):
    """The one line the program prints for an error, without its 'rayform: error: ' prefix."""
    r = run_cli(*args, check=False)
    assert r.returncode != 0
    line = r.stderr.strip().splitlines()[-1]
    prefix = "rayform: error: "
    assert line.startswith(prefix), r.stderr
    return line[len(prefix):]


def test_error_is_a_runtime_error(rayform):
    assert issubclass(rayform.Error, RuntimeError)


def test_a_missing_file_is_the_programs_error(rayform, tmp_path):
    missing = tmp_path / "nothing_here.glb"
    with pytest.raises(rayform.Error) as e:
        rayform.load(missing)
    assert str(e.value) == cli_error("render", missing, "-o", tmp_path / "x.png")
    assert str(missing) in str(e.value)


def test_a_bad_file_is_the_programs_error_with_its_place(rayform, tmp_path):
    bad = tmp_path / "bad.gltf"
    bad.write_text('{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}], '
                   '"nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}')
    with pytest.raises(rayform.Error) as e:
        rayform.render(bad, size=SIZE)
    assert str(e.value) == cli_error("render", bad, "-o", tmp_path / "x.png")
    assert str(e.value).startswith(f"{bad}: meshes[0].primitives[0].attributes.POSITION:")  # the JSON path
    txt = tmp_path / "bad.txt"
    txt.write_text("PerspectiveCamera {\n    center 0 0 oops\n}\n")
    with pytest.raises(rayform.Error) as e:
        rayform.load(txt)
    assert str(e.value) == cli_error("info", txt)
    assert str(e.value).startswith(f"{txt}:2:16:")  # line:column


@pytest.mark.parametrize(
    "kwargs, error, name",
    [
        ({"spp": 0}, ValueError, "spp"),
        ({"size": (0, 10)}, ValueError, "size"),
        ({"size": "64x48"}, TypeError, "size"),
        ({"spp": "four"}, TypeError, "spp"),
        ({"bounces": -1}, ValueError, "bounces"),
        ({"orbit": (0, 95)}, ValueError, "orbit"),
        ({"orbit": (0, 10), "look_from": (1, 2, 3)}, ValueError, "orbit"),
        ({"fov": 180}, ValueError, "fov"),
        ({"background": (2, 0, 0)}, ValueError, "background"),
        ({"aovs": ("depth", "motion")}, ValueError, "aovs"),
        ({"tonemap": "filmic"}, ValueError, "tonemap"),
        ({"shadow": True}, TypeError, "shadow"),
    ],
)
def test_a_bad_argument_names_itself(rayform, kwargs, error, name):
    with pytest.raises(error) as e:
        rayform.render(OBJ, **kwargs)
    assert name in str(e.value)
    assert not isinstance(e.value, rayform.Error)


def test_a_bad_load_option_names_itself(rayform):
    with pytest.raises(ValueError, match="triangle"):
        rayform.load(OBJ, triangle=5)
    with pytest.raises(ValueError, match="dialect"):
        rayform.load(COURSE, dialect="1999")
    with pytest.raises(TypeError, match="path"):
        rayform.load(42)
    # A limit below the file's: the reader's message, as the program's.
    with pytest.raises(rayform.Error, match="triangles"):
        rayform.load(OBJ, triangles=1)


def test_ctrl_c_stops_a_render_at_once(rayform):
    prepared = rayform.prepare(GLB)
    prepared.render(size=(32, 32))  # BVHs built: what follows is the render alone
    options = dict(size=(1024, 1024), spp=64, threads=1)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        prepared.render(**options)
    stopped = time.monotonic() - start
    timer.join()
    # One thread, 64 samples a pixel of a 1024x1024 picture takes many
    # seconds; stopped between tiles it ends well within a second of the signal.
    assert stopped < 1.5, f"took {stopped:.2f} s to stop"
    # The prepared scene still renders after it.
    assert prepared.render(size=(16, 16))["color"].shape == (16, 16, 3)


def test_a_scene_outlives_its_files(rayform, tmp_path):
    # A .gltf with a .bin and PNG textures beside it: every file removed after load.
    folder = tmp_path / "copy"
    shutil.copytree(GLTF.parent, folder)
    scene = rayform.load(folder / GLTF.name)
    expected = rayform.render(GLTF, size=SIZE, color8=True)
    shutil.rmtree(folder)
    got = rayform.render(scene, size=SIZE, color8=True)
    assert np.array_equal(got["color"], expected["color"])
    assert np.array_equal(got["color8"], expected["color8"])


def test_two_threads_render_what_one_does(rayform):
    files = [GLB, OBJ, COURSE, GLB]
    kwargs = [dict(size=SIZE, orbit=(40, 10)), dict(size=SIZE, spp=3), dict(size=SIZE, shadows=True),
              dict(size=SIZE, spp=2, transparent=True)]
    alone = [rayform.render(f, **k) for f, k in zip(files, kwargs)]
    results = [None] * len(files)

    def work(i):
        for _ in range(3):
            results[i] = rayform.render(files[i], **kwargs[i])

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(files))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, results):
        assert np.array_equal(a["color"], b["color"])


def test_threads_making_the_first_render_at_once(tmp_path):
    # A fresh process whose first two renders start together: they once
    # deadlocked on NumPy's C API, looked up on first use.
    script = (
        "import threading, rayform\n"
        f"ts = [threading.Thread(target=rayform.render, args=({str(OBJ)!r},), kwargs=dict(size=(8, 8))) "
        "for _ in range(4)]\n"
        "[t.start() for t in ts]\n[t.join() for t in ts]\nprint('done')\n")
    for _ in range(3):
        r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0 and r.stdout == "done\n", r.stderr


def test_render_releases_the_gil(rayform):
    # While one thread renders, another runs Python code.
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.005)

    t = threading.Thread(target=tick)
    t.start()
    start = time.monotonic()
    rayform.render(GLB, size=(256, 256), spp=8, threads=1)
    end = time.monotonic()
    done.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    assert end - start > 0.1 and len(during) >= (end - start) / 0.05


def test_arrays_own_their_memory(rayform):
    r = rayform.render(OBJ, size=SIZE, aovs=("depth", "normal", "albedo"), color8=True)
    for name, a in r.items():
        assert a.flags["C_CONTIGUOUS"], name
        assert not a.flags["OWNDATA"] and a.base is not None, name  # held by the module's buffer, not copied
    assert r["color"].dtype == np.float32 and r["depth"].dtype == np.float32


def test_scene_views(rayform):
    scene = rayform.load(COURSE)
    assert scene.format == "course" and scene.dialect == "2012"
    assert len(scene.cameras) == 1 and scene.cameras[0]["fov"] == pytest.approx(36)
    assert len(scene.lights) == 3 and scene.lights[0]["kind"] == "directional"
    assert len(scene.materials) > 0
    assert scene.counts["lights"] == 3
    obj = rayform.load(OBJ)
    assert obj.format == "obj" and obj.dialect is None and obj.cameras == ()
    assert any("no camera" in n for n in obj.notes)
    lo, hi = obj.bounds
    assert all(a < b for a, b in zip(lo, hi))
    with pytest.raises(AttributeError):
        obj.cameras = ()


def test_info_is_the_programs_json(rayform):
    for f in (COURSE, OBJ, GLB):
        text = run_cli("info", "--json", f).stdout
        assert rayform.load(f).info() + "\n" == text
        assert json.loads(text)["scene"] == str(f)


def test_convert_writes_what_the_program_writes(rayform, tmp_path):
    (tmp_path / "py").mkdir()
    (tmp_path / "cli").mkdir()
    r = rayform.convert(GLB, tmp_path / "py" / "model.obj")
    run_cli("convert", GLB, tmp_path / "cli" / "model.obj", "-q")
    assert r["files"][0] == str(tmp_path / "py" / "model.obj") and len(r["files"]) >= 2  # the .obj and its .mtl
    written = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == written
    for name in written:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    with pytest.raises(ValueError, match="dst"):
        rayform.convert(GLB, tmp_path / "x.unknown")


def test_convert_checks_out_dir_as_the_program(rayform, tmp_path):
    # The same checks as `rayform convert --out-dir` (pipeline/convert_checks.h), before anything is read.
    (tmp_path / "assets").mkdir()
    with pytest.raises(ValueError) as e:
        rayform.convert(GLB, tmp_path / "m.obj", out_dir=tmp_path / "nothere")
    assert str(e.value) == f"out_dir: folder '{tmp_path / 'nothere'}' does not exist"
    with pytest.raises(ValueError) as e:
        rayform.convert(GLB, tmp_path / "m.glb", out_dir=tmp_path / "assets")
    assert str(e.value) == "out_dir: a .glb holds everything in one file: there are no side files"
    with pytest.raises(ValueError) as e:
        rayform.convert(GLB, tmp_path / "m.gltf", out_dir=tmp_path / "assets", embed=True)
    assert str(e.value) == "out_dir: with embed=True the .gltf holds everything: there are no side files"
    assert not list(tmp_path.glob("m.*")) and not list((tmp_path / "assets").iterdir())
    r = rayform.convert(GLB, tmp_path / "m.gltf", out_dir=tmp_path / "assets")
    assert r["files"][0] == str(tmp_path / "m.gltf") and list((tmp_path / "assets").iterdir())


def test_write_image_round_trips(rayform, tmp_path):
    r = rayform.render(GLB, size=SIZE, color8=True, transparent=True)
    rayform.write_image(tmp_path / "a.png", r["color8"])
    assert np.array_equal(read_png(tmp_path / "a.png"), r["color8"])
    run_cli("render", GLB, "-o", tmp_path / "cli.png", "--size", f"{SIZE[0]}x{SIZE[1]}", "--transparent", "-q")
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    with pytest.raises(ValueError, match="channels"):
        rayform.write_image(tmp_path / "b.png", np.zeros((4, 4, 2), np.uint8))


def test_help_documents_every_argument(rayform):
    doc = rayform.render.__doc__
    for name in ("size", "camera", "orbit", "look_from", "look_at", "fov", "spp", "target_error", "shadows",
                 "bounces", "background", "transparent", "aovs", "threads", "color8"):
        assert f"{name}:" in doc or f"{name}," in doc, name
    assert rayform.load.__doc__ and rayform.prepare.__doc__ and rayform.convert.__doc__
