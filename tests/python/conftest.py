# Shared by the Python module's tests (tests/python, ctest label python):
# where the module, the rayform program and the data are, the program run
# on the same file and options, and its pictures read back as arrays.
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ.get("RAYFORM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SHARED = pathlib.Path(os.environ.get("RAYFORM_SHARED", SOURCE.parent / "shared"))
BIN = os.environ.get("RAYFORM_BIN", str(SOURCE / "build" / "cli" / "rayform"))

# The repository's own scenes: one of each format.
COURSE = SOURCE / "scenes" / "default.txt"
OBJ = SOURCE / "scenes" / "assets" / "materials.obj"
GLB = SOURCE / "scenes" / "assets" / "features.glb"
GLTF = SOURCE / "scenes" / "assets" / "features.gltf"


def run_cli(*args, check=True):
    """Runs the rayform program; returns the CompletedProcess (text)."""
    r = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"rayform {' '.join(map(str, args))} failed:\n{r.stderr}")
    return r


def read_png(path):
    from PIL import Image

    with Image.open(path) as im:
        return np.asarray(im).copy()


def read_exr(path):
    """An EXR's channels as float32 (h, w, c), as stored (rayform.read_image: OpenImageIO)."""
    import rayform

    return rayform.read_image(path)


@pytest.fixture(scope="session")
def rayform():
    import rayform as module

    return module


def need_shared(*parts):
    """The path under RAYFORM_SHARED, or the test skipped (fails in CI) when it is absent."""
    p = SHARED.joinpath(*parts)
    if not p.exists():
        if os.environ.get("CI"):
            pytest.fail(f"third-party data not found at {p} (required in CI)")
        pytest.skip(f"third-party data not found at {p} (set RAYFORM_SHARED)")
    return p
