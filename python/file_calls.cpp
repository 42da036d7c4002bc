// rayform.convert and rayform.write_image: files written as the command line
// writes them (`rayform convert`; image/image.h), to a temporary renamed into
// place.
#include "module_parts.h"
#include "rayform/base/file_extension.h"
#include "rayform/image/image.h"
#include "rayform/image/interrupt_cleanup.h"
#include "rayform/importers/scene_writer.h"
#include "rayform/pipeline/convert_checks.h"
#include "rayform/pipeline/job_outputs.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <csignal>
#include <cstring>

namespace rayform::python {
namespace {

py::dict convert(const std::string& src, const std::string& dst, const py::kwargs& kwargs) {
  SaveOptions save;
  py::kwargs load;
  std::optional<std::string> out_dir;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key).cast<std::string>();
    if (name == "flatten") save.flatten = value.cast<bool>();
    else if (name == "embed") save.embed = value.cast<bool>();
    else if (name == "sphere_segments") {
      save.sphere_segments = value.cast<int>();
      if (save.sphere_segments < min_sphere_segments || save.sphere_segments > max_sphere_segments)
        throw py::value_error("sphere_segments: expected " + std::to_string(min_sphere_segments) + " to " +
                              std::to_string(max_sphere_segments) + ", got " + std::to_string(save.sphere_segments));
    } else if (name == "tessellate_only") save.shape_extras = !value.cast<bool>();
    else if (name == "out_dir") out_dir = path_argument(value, "out_dir");
    else load[key] = value;  // dialect, limits, ...: as load()
  }
  // Before reading, as the command line (convert_checks.h).
  if (std::string problem = convert_output_problem(src, dst); !problem.empty())
    throw py::value_error("dst: " + problem);
  check_output_folder(dst, "the scene");
  if (out_dir) {
    if (std::string problem = side_folder_problem(dst, *out_dir, save.embed, "embed=True"); !problem.empty())
      throw py::value_error("out_dir: " + problem);
    save.side_folder = *out_dir;
  }
  SceneObject scene = load_scene_object(src, load, false);
  save.dialect = convert_dialect(scene.load.dialect, *scene.loaded);
  std::vector<std::string> messages;
  SaveResult r;
  {
    py::gil_scoped_release unlocked;
    r = save_scene(scene.loaded->scene, dst, save, &messages);
  }
  py::dict out;
  out["files"] = py::cast(r.files);
  out["notes"] = py::cast(messages);
  out["warnings"] = py::cast(scene.loaded->warnings);
  return out;
}

void write_image_array(const std::string& path, const py::array& array) {
  if (array.ndim() != 2 && array.ndim() != 3)
    throw py::value_error("array: expected (height, width) or (height, width, channels), got " +
                          std::to_string(array.ndim()) + " dimensions");
  const int h = int(array.shape(0)), w = int(array.shape(1)), c = array.ndim() == 3 ? int(array.shape(2)) : 1;
  if (c != 1 && c != 3 && c != 4) throw py::value_error("array: expected 1, 3 or 4 channels, got " + std::to_string(c));
  if (h < 1 || w < 1) throw py::value_error("array: empty");
  if (array.dtype().is(py::dtype::of<uint8_t>())) {
    if (!is_8bit_image_path(path))
      throw py::value_error("path: " + path + ": uint8 arrays are written to 8-bit files (.png, .bmp, .tga, .jpg)");
    auto a = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(array);
    Image8 image{w, h, c, std::vector<unsigned char>(a.data(), a.data() + a.size())};
    py::gil_scoped_release unlocked;
    commit_temporary(write_image8_temporary(path, image), path);
    return;
  }
  if (array.dtype().kind() != 'f')
    throw py::type_error("array: expected float32/float64 or uint8 values, got dtype " +
                         py::str(array.dtype()).cast<std::string>());
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
  Image image(w, h, c);
  std::memcpy(image.pixels.data(), a.data(), image.pixels.size() * sizeof(float));
  py::gil_scoped_release unlocked;
  write_image(path, image);
}

py::array read_image_array(const std::string& path) {
  Image image;
  {
    py::gil_scoped_release unlocked;
    image = read_image(path);
  }
  const std::vector<py::ssize_t> shape{image.height, image.width, image.channels};
  auto* held = new std::vector<float>(std::move(image.pixels));
  py::capsule owner(held, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>(shape, held->data(), owner);
}

}  // namespace

void add_files(py::module_& m) {
  // The library's cleanup of temporaries on SIGINT/SIGTERM/SIGHUP
  // (interrupt_cleanup.h) would end the Python process: its handlers are
  // installed once, here, and Python's put back at once.
  {
    const int signals[] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction saved[3]{};
    for (int i = 0; i < 3; ++i) sigaction(signals[i], nullptr, &saved[i]);
    set_interrupt_message("");
    for (int i = 0; i < 3; ++i) sigaction(signals[i], &saved[i], nullptr);
  }
  m.def(
      "convert",
      [](const py::object& src, const py::object& dst, const py::kwargs& options) {
        return convert(path_argument(src, "src"), path_argument(dst, "dst"), options);
      },
      py::arg("src"), py::arg("dst"),
      R"(convert(src, dst, *, flatten=False, embed=False, sphere_segments=64, tessellate_only=False,
        out_dir=None, dialect=None, **limits) -> dict

Converts a scene between course .txt, OBJ+MTL, .gltf and .glb, as `rayform
convert` (the extension of dst decides; docs/convert.md). dialect and limits
as load()'s. Returns {'files': [written, main first], 'notes': [what dst
cannot hold], 'warnings': [the reader's]}. Raises rayform.Error, ValueError.)");
  m.def(
      "read_image", [](const py::object& path) { return read_image_array(path_argument(path, "path")); },
      py::arg("path"),
      R"(read_image(path) -> numpy.ndarray

Reads an image file (.png, .jpg, .exr, .hdr, .tif, ... as rayform reads
textures): float32 (h, w, channels), rows from the top; 8-bit samples as
v / 255, 16-bit as v / 65535, float samples as stored. Raises rayform.Error.)");
  m.def(
      "write_image",
      [](const py::object& path, const py::array& array) { write_image_array(path_argument(path, "path"), array); },
      py::arg("path"), py::arg("array"),
      R"(write_image(path, array) -> None

Writes an (h, w), (h, w, 3) or (h, w, 4) array to an image file by its extension
(.png, .bmp, .tga, .jpg, .exr, .hdr, .tif): uint8 values as they are (8-bit
files), floats as 8-bit files quantise them (clamped to 0..1, no encoding:
pass color8 for sRGB) or as float files store them. Written to a temporary,
then renamed. Raises rayform.Error, ValueError, TypeError.)");
}

}  // namespace rayform::python
