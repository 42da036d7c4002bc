# rayform.render against the rayform program on third-party files
# (RAYFORM_SHARED: the duck as OBJ and glTF, Khronos samples, a course scene);
# skipped when the data is absent.
import numpy as np
import pytest

from conftest import need_shared, read_png, run_cli

SIZE = (96, 96)
FILES = [
    ("assets", "duck", "duck.obj"),
    ("assets", "duck", "duck.gltf"),
    ("assets", "khronos", "Avocado", "glTF", "Avocado.gltf"),
    ("assets", "khronos", "TransmissionTest", "glTF-Binary", "TransmissionTest.glb"),
    ("assets", "khronos", "AlphaBlendModeTest", "glTF-Binary", "AlphaBlendModeTest.glb"),
    ("course", "2012", "scene07_shine.txt"),
    ("course", "2019", "scene03_sphere.txt"),
    ("course", "2012-a5", "scene10_sphere.txt"),
]


@pytest.mark.parametrize("parts", FILES, ids=lambda p: p[-1])
def test_color8_equals_the_png(rayform, tmp_path, parts):
    path = need_shared(*parts)
    for kwargs, flags in [({}, []), ({"spp": 3, "shadows": True, "transparent": True},
                                     ["--spp", "3", "--shadows", "--transparent"])]:
        run_cli("render", path, "-o", tmp_path / "c.png", "--size", f"{SIZE[0]}x{SIZE[1]}", "-q", *flags)
        a = rayform.render(path, size=SIZE, color=False, color8=True, **kwargs)["color8"]
        png = read_png(tmp_path / "c.png")
        assert a.shape == png.shape and np.array_equal(a, png), parts
