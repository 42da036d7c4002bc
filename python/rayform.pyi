# Type stubs of the rayform module (python/*.cpp; docs/python.md).
import os
from typing import Any, Literal, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, os.PathLike[str]]
Vec3 = Tuple[float, float, float]

class Error(RuntimeError):
    """A file that cannot be read or written, or a render that failed: str(e) is
    the one line the command line prints."""

class Scene:
    """A scene read by load(): read-only; outlives its file."""
    @property
    def path(self) -> str: ...
    @property
    def format(self) -> Literal["course", "obj", "gltf"]: ...
    @property
    def dialect(self) -> Union[Literal["2012", "2019", "a5"], None]: ...
    @property
    def counts(self) -> dict[str, int]: ...
    @property
    def bounds(self) -> Union[Tuple[Vec3, Vec3], None]: ...
    @property
    def cameras(self) -> Tuple[dict[str, Any], ...]: ...
    @property
    def lights(self) -> Tuple[dict[str, Any], ...]: ...
    @property
    def materials(self) -> Tuple[dict[str, Any], ...]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def notes(self) -> list[str]: ...
    def info(self) -> str:
        """The JSON text of `rayform info --json`."""

class Prepared:
    """A scene whose meshes' BVHs are kept from one render to the next."""
    @property
    def scene(self) -> Scene: ...
    def render(
        self,
        *,
        size: Union[Tuple[int, int], None] = None,
        camera: Union[int, None] = None,
        orbit: Union[Sequence[float], None] = None,
        frame: bool = False,
        look_from: Union[Vec3, None] = None,
        look_at: Union[Vec3, None] = None,
        up: Union[Vec3, None] = None,
        fov: Union[float, None] = None,
        spp: Union[int, None] = None,
        target_error: Union[float, None] = None,
        max_spp: Union[int, None] = None,
        shadows: bool = False,
        bounces: Union[int, None] = None,
        background: Union[Vec3, str, None] = None,
        transparent: bool = False,
        exposure: float = 0.0,
        tonemap: Union[Literal["khr-neutral", "aces", "none"], None] = None,
        encoding: Literal["auto", "raw", "srgb"] = "auto",
        env: Union[PathLike, None] = None,
        env_intensity: Union[float, None] = None,
        env_rotate: Union[float, None] = None,
        filter: Literal["box", "tent"] = "box",
        sampler: Literal["stratified", "random"] = "stratified",
        aovs: Sequence[Literal["depth", "normal", "albedo"]] = (),
        color: bool = True,
        color8: bool = False,
        threads: int = 0,
    ) -> dict[str, npt.NDArray[Any]]: ...

def load(
    path: PathLike,
    *,
    dialect: Union[Literal["2012", "2019", "a5"], None] = None,
    flat: bool = False,
    gltf_scene: int = -1,
    confine: bool = False,
    **limits: Union[int, str],
) -> Scene: ...
def render(
    scene: Union[Scene, Prepared, PathLike],
    *,
    size: Union[Tuple[int, int], None] = None,
    camera: Union[int, None] = None,
    orbit: Union[Sequence[float], None] = None,
    frame: bool = False,
    look_from: Union[Vec3, None] = None,
    look_at: Union[Vec3, None] = None,
    up: Union[Vec3, None] = None,
    fov: Union[float, None] = None,
    spp: Union[int, None] = None,
    target_error: Union[float, None] = None,
    max_spp: Union[int, None] = None,
    shadows: bool = False,
    bounces: Union[int, None] = None,
    background: Union[Vec3, str, None] = None,
    transparent: bool = False,
    exposure: float = 0.0,
    tonemap: Union[Literal["khr-neutral", "aces", "none"], None] = None,
    encoding: Literal["auto", "raw", "srgb"] = "auto",
    env: Union[PathLike, None] = None,
    env_intensity: Union[float, None] = None,
    env_rotate: Union[float, None] = None,
    filter: Literal["box", "tent"] = "box",
    sampler: Literal["stratified", "random"] = "stratified",
    aovs: Sequence[Literal["depth", "normal", "albedo"]] = (),
    color: bool = True,
    color8: bool = False,
    threads: int = 0,
) -> dict[str, npt.NDArray[Any]]:
    """Renders into arrays: 'color' float32 (h, w, 3|4) linear, 'color8' uint8
    sRGB, 'depth' (h, w), 'normal' and 'albedo' (h, w, 3)."""

def prepare(scene: Union[Scene, PathLike], **load_options: Any) -> Prepared: ...
def convert(
    src: PathLike,
    dst: PathLike,
    *,
    flatten: bool = False,
    embed: bool = False,
    sphere_segments: int = 64,
    tessellate_only: bool = False,
    out_dir: Union[PathLike, None] = None,
    dialect: Union[Literal["2012", "2019", "a5"], None] = None,
    **limits: Union[int, str],
) -> dict[str, list[str]]: ...
def read_image(path: PathLike) -> npt.NDArray[np.float32]: ...
def write_image(path: PathLike, array: npt.NDArray[Union[np.uint8, np.float32, np.float64]]) -> None: ...
