# rayform.render's arrays against the rayform program's files of the same
# scene and options: color8 = the PNG byte for byte, color = the EXR's
# floats, the per-pixel outputs = the program's depth, normals and albedo
# pictures (after the course's mapping that the program applies).
import numpy as np
import pytest

from conftest import COURSE, GLB, OBJ, read_exr, read_png, run_cli

SCENES = {"course": COURSE, "obj": OBJ, "glb": GLB}

# (keyword arguments, the same as flags)
OPTIONS = {
    "default": ({}, []),
    "spp_shadows": ({"spp": 4, "shadows": True}, ["--spp", "4", "--shadows"]),
    "transparent": ({"transparent": True, "spp": 2}, ["--transparent", "--spp", "2"]),
    "orbit_background": ({"orbit": (30, 20), "background": (0.2, 0.4, 0.6)},
                         ["--orbit", "30,20", "--background", "0.2,0.4,0.6"]),
}
SIZE = (72, 56)


def cli_flags(flags):
    return ["--size", f"{SIZE[0]}x{SIZE[1]}", "-q", *flags]


@pytest.mark.parametrize("option", OPTIONS)
@pytest.mark.parametrize("scene", SCENES)
def test_color8_equals_the_png(rayform, tmp_path, scene, option):
    kwargs, flags = OPTIONS[option]
    out = tmp_path / "c.png"
    run_cli("render", SCENES[scene], "-o", out, *cli_flags(flags))
    got = rayform.render(SCENES[scene], size=SIZE, color=False, color8=True, **kwargs)
    png = read_png(out)
    assert set(got) == {"color8"}
    a = got["color8"]
    assert a.dtype == np.uint8 and a.shape == png.shape, (a.shape, png.shape)
    assert a.shape[2] == (4 if option == "transparent" else 3)
    assert np.array_equal(a, png), f"{int((a != png).sum())} samples differ"
    assert a.std() > 0  # a picture, not a flat colour


@pytest.mark.parametrize("option", OPTIONS)
@pytest.mark.parametrize("scene", SCENES)
def test_color_equals_the_exr(rayform, tmp_path, scene, option):
    kwargs, flags = OPTIONS[option]
    out = tmp_path / "c.exr"
    run_cli("render", SCENES[scene], "-o", out, *cli_flags(flags))
    got = rayform.render(SCENES[scene], size=SIZE, **kwargs)
    exr = read_exr(out)
    a = got["color"]
    assert a.dtype == np.float32 and a.shape == exr.shape, (a.shape, exr.shape)
    assert np.array_equal(a, exr), f"max difference {np.abs(a - exr).max()}"


@pytest.mark.parametrize("scene", SCENES)
def test_aovs_equal_the_programs_pictures(rayform, tmp_path, scene):
    lo, hi = 2.0, 14.0
    run_cli("render", SCENES[scene], "-o", tmp_path / "c.exr", "--depth", f"{lo}:{hi}:{tmp_path / 'd.exr'}",
            "--normals", tmp_path / "n.exr", "--albedo", tmp_path / "a.exr", *cli_flags([]))
    got = rayform.render(SCENES[scene], size=SIZE, aovs=("depth", "normal", "albedo"))
    depth, normal, albedo = got["depth"], got["normal"], got["albedo"]
    assert depth.shape == SIZE[::-1] and normal.shape == (*SIZE[::-1], 3) and albedo.shape == normal.shape
    assert np.isfinite(depth).any() and np.isinf(depth).any()
    # The course 2012 dialect and assets: near-white depth (render/aov_images.h).
    lo32, hi32 = np.float32(lo), np.float32(hi)
    with np.errstate(invalid="ignore"):
        grey = np.where(depth < lo32, np.float32(1), np.where(depth > hi32, np.float32(0), (hi32 - depth) / (hi32 - lo32)))
    grey = np.where(np.isfinite(depth), grey, np.float32(0)).astype(np.float32)
    assert np.array_equal(np.repeat(grey[:, :, None], 3, axis=2), read_exr(tmp_path / "d.exr"))
    if scene == "course":  # 2012: absolute values
        shown = np.abs(normal)
    else:  # (n + 1) / 2, 0.5 where nothing is hit
        miss = (normal == 0).all(axis=2, keepdims=True)
        shown = np.where(miss, np.float32(0.5), np.float32(0.5) * (normal + np.float32(1)))
    assert np.array_equal(shown.astype(np.float32), read_exr(tmp_path / "n.exr"))
    hit = (normal != 0).any(axis=2)
    assert np.allclose(np.linalg.norm(normal[hit], axis=1), 1, atol=1e-5)
    assert np.array_equal(albedo, read_exr(tmp_path / "a.exr"))


def test_the_defaults_are_the_programs(rayform, tmp_path):
    # No size, no bounces, no tone map given: the scene's defaults (512x512
    # for a glTF file, its PBR bounces and tone map) in both.
    run_cli("render", GLB, "-o", tmp_path / "c.png", "-q")
    a = rayform.render(GLB, color=False, color8=True)["color8"]
    assert a.shape == (512, 512, 3)
    assert np.array_equal(a, read_png(tmp_path / "c.png"))


def test_a_prepared_scene_renders_what_render_does(rayform, tmp_path):
    prepared = rayform.prepare(GLB)
    for az in (0, 90, 200):
        run_cli("render", GLB, "-o", tmp_path / f"{az}.png", "--orbit", f"{az},15", *cli_flags([]))
        a = prepared.render(size=SIZE, orbit=(az, 15), color8=True)
        assert np.array_equal(a["color8"], read_png(tmp_path / f"{az}.png"))
        b = rayform.render(prepared.scene, size=SIZE, orbit=(az, 15))
        assert np.array_equal(a["color"], b["color"])
