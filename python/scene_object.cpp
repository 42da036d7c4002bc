// rayform.load and rayform.Scene: a file read once, its counts, bounds,
// cameras, lights and materials as read-only views (tuples and dicts built
// on each access), warnings and notes, and info() as `rayform info --json`.
#include "module_parts.h"
#include "rayform/base/error.h"
#include "rayform/base/limits.h"
#include "rayform/importers/course_txt/course_dialect.h"
#include "rayform/pipeline/scene_info.h"
#include "rayform/pipeline/scene_ready.h"
#include "rayform/scene/scene_stats.h"

#include "rayform/image/image.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace rayform::python {
namespace {

py::tuple vec(const vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

// dialect=: "2012", "2019" or "a5" (as the command line's --dialect).
std::optional<CourseDialect> dialect_argument(const py::handle& value) {
  if (value.is_none()) return std::nullopt;
  const std::string d = py::str(value).cast<std::string>();
  if (d == "2012") return CourseDialect::v2012;
  if (d == "2019") return CourseDialect::v2019;
  if (d == "a5") return CourseDialect::a5;
  throw py::value_error("dialect: expected '2012', '2019' or 'a5', got '" + d + "'");
}

const char* light_kind(Light::Kind k) {
  return k == Light::Kind::directional ? "directional" : k == Light::Kind::point ? "point" : "spot";
}

py::dict camera_view(const Camera& c) {
  py::dict d;
  d["name"] = c.name;
  d["projection"] = c.projection == Camera::Projection::perspective ? "perspective" : "orthographic";
  d["center"] = vec(c.center);
  d["direction"] = vec(c.direction);
  d["up"] = vec(c.up);
  d["fov"] = c.fov_deg;
  d["ortho_height"] = c.ortho_height;
  return d;
}

py::dict light_view(const Light& l) {
  py::dict d;
  d["name"] = l.name;
  d["kind"] = light_kind(l.kind);
  d["direction"] = vec(l.direction);
  d["position"] = vec(l.position);
  d["color"] = vec(l.color);
  return d;
}

py::dict material_view(const Material& m) {
  py::dict d;
  d["name"] = m.name;
  d["model"] = m.model == Material::Model::phong ? "phong" : "metallic_roughness";
  d["diffuse"] = vec(m.diffuse);
  d["specular"] = vec(m.specular);
  d["shininess"] = m.shininess;
  d["emission"] = vec(m.emission);
  d["texture"] = m.diffuse_texture;
  d["double_sided"] = m.double_sided;
  d["unlit"] = m.unlit;
  return d;
}

template <class T, class F>
py::tuple views(const std::vector<T>& items, F view) {
  py::tuple t(items.size());
  for (size_t i = 0; i < items.size(); ++i) t[i] = view(items[i]);
  return t;
}

py::list strings(const std::vector<std::string>& v) {
  py::list l;
  for (const std::string& s : v) l.append(s);
  return l;
}

// The texture files a scene names, decoded into it (Texture::pixels), so that
// the Scene renders when its files are gone: prepare_scene reads a texture's
// file only when it has no pixels (render/texture_sampler.h: decode_texture),
// and decodes the same 8-bit values from either. A file that cannot be read
// now is left for prepare, which then reports it as the command line does;
// 16-bit and float pictures too (decode_texture converts them itself).
void decode_texture_files(LoadedScene& loaded, const Limits& limits) {
  std::vector<Texture>& textures = loaded.scene.textures;
  tbb::parallel_for(size_t(0), textures.size(), [&](size_t i) {
    Texture& t = textures[i];
    if (!t.pixels.empty() || t.path.empty()) return;
    try {
      DecodedImage file = read_image_file(t.path, DecodeOptions{limits.texture_texels});
      if (file.bits != 8) return;
      t.width = file.width;
      t.height = file.height;
      t.channels = file.channels;
      t.pixels = std::move(file.bytes);
    } catch (const std::exception&) {
    }
  });
}

}  // namespace

SceneObject load_scene_object(const std::string& path, const py::kwargs& options, bool decode_textures) {
  SceneObject s;
  s.path = path;
  for (const auto& [key, value] : options) {
    const std::string name = py::str(key).cast<std::string>();
    if (name == "dialect") {
      s.load.dialect = dialect_argument(value);
    } else if (name == "flat") {
      s.load.flat_normals = value.cast<bool>();
    } else if (name == "gltf_scene") {
      s.load.gltf_scene = value.cast<int>();
    } else if (name == "confine") {
      s.load.access.confine = value.cast<bool>();
    } else {
      // A limit (base/limits.h), its name with _ for the command line's -.
      std::string limit = name;
      std::replace(limit.begin(), limit.end(), '_', '-');
      if (!py::isinstance<py::int_>(value) && !py::isinstance<py::str>(value))
        throw py::type_error(name + ": expected an int, got " +
                             py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
      if (std::string problem = set_limit(s.load.limits, limit, py::str(value).cast<std::string>()); !problem.empty())
        throw py::value_error(problem);
    }
  }
  py::gil_scoped_release unlocked;
  LoadedScene loaded = load_scene(path, s.load);
  if (decode_textures) decode_texture_files(loaded, s.load.limits);
  s.loaded = std::make_shared<const LoadedScene>(std::move(loaded));
  return s;
}

void add_scene(py::module_& m) {
  py::class_<SceneObject>(m, "Scene",
                          "A scene read by rayform.load: read-only; it outlives its file and renders any number of "
                          "times (rayform.render, rayform.prepare).")
      .def_property_readonly(
          "path", [](const SceneObject& s) { return s.path; }, "The path it was read from.")
      .def_property_readonly(
          "format",
          [](const SceneObject& s) {
            return s.loaded->format == SceneFormat::course_txt ? "course"
                   : s.loaded->format == SceneFormat::obj      ? "obj"
                                                               : "gltf";
          },
          "'course', 'obj' or 'gltf'.")
      .def_property_readonly(
          "dialect",
          [](const SceneObject& s) -> py::object {
            if (s.loaded->format != SceneFormat::course_txt) return py::none();
            return py::str(std::string(course_dialect_name(s.loaded->dialect)));
          },
          "Course scenes: the dialect read ('2012', '2019', 'a5'); else None.")
      .def_property_readonly(
          "counts",
          [](const SceneObject& s) {
            const SceneStats st = scene_stats(s.loaded->scene, s.load.limits.instances);
            py::dict d;
            d["nodes"] = st.nodes;
            d["instances"] = st.instances;
            d["spheres"] = st.spheres;
            d["planes"] = st.planes;
            d["triangles"] = st.triangles;
            d["mesh_triangles"] = st.mesh_triangles;
            d["meshes"] = st.meshes;
            d["unique_mesh_triangles"] = st.unique_mesh_triangles;
            d["materials"] = st.materials;
            d["textures"] = st.textures;
            d["lights"] = st.lights;
            d["cameras"] = st.cameras;
            return d;
          },
          "What the scene holds, as `rayform info` counts it (a dict of ints).")
      .def_property_readonly(
          "bounds",
          [](const SceneObject& s) -> py::object {
            const Bounds3 b = scene_stats(s.loaded->scene, s.load.limits.instances).bounds;
            if (b.empty()) return py::none();
            return py::make_tuple(vec(b.lo), vec(b.hi));
          },
          "((xmin, ymin, zmin), (xmax, ymax, zmax)) in world units, planes excluded; None when empty.")
      .def_property_readonly(
          "cameras", [](const SceneObject& s) { return views(s.loaded->scene.cameras, camera_view); },
          "The file's cameras (a tuple of dicts).")
      .def_property_readonly(
          "lights", [](const SceneObject& s) { return views(s.loaded->scene.lights, light_view); },
          "The file's lights (a tuple of dicts).")
      .def_property_readonly(
          "materials", [](const SceneObject& s) { return views(s.loaded->scene.materials, material_view); },
          "The file's materials (a tuple of dicts).")
      .def_property_readonly(
          "warnings", [](const SceneObject& s) { return strings(s.loaded->warnings); },
          "What the reader warned of, one line each.")
      .def_property_readonly(
          "notes",
          [](const SceneObject& s) {
            ReadyOptions ro;
            ro.load = s.load;
            const ReadyScene ready = make_scene_ready(*s.loaded, s.path, ro);
            std::vector<std::string> notes = ready.notes;
            if (!ready.bounces_note.empty()) notes.push_back(ready.bounces_note);
            return strings(notes);
          },
          "What the defaults of a first picture add (a camera, lights), one line each, as the command line notes.")
      .def(
          "info",
          [](const SceneObject& s) {
            return scene_info_json(s.path, *s.loaded, scene_stats(s.loaded->scene, s.load.limits.instances));
          },
          "The JSON text `rayform info --json` prints for this file (json.loads it).")
      .def("__repr__", [](const SceneObject& s) { return "<rayform.Scene '" + s.path + "'>"; });

  m.def(
      "load",
      [](const py::object& path, const py::kwargs& options) {
        return load_scene_object(path_argument(path, "path"), options);
      },
      py::arg("path"),
      R"(load(path, *, dialect=None, flat=False, gltf_scene=-1, confine=False, **limits) -> Scene

Reads a course .txt, OBJ, .gltf or .glb file.

path: str or os.PathLike.
dialect: course scenes: '2012', '2019' or 'a5' (default: detected).
flat: OBJ: faceted normals where the file has none (default smooth).
gltf_scene: glTF: the scene to read (-1: the file's default).
confine: read only files in the scene's folder and below.
**limits: triangles=, vertices=, instances=, texture_texels=, json_depth=: the
  command line's --limit NAME=VALUE (an int, or a str with a k/M/G suffix).

Raises rayform.Error for a missing or bad file, ValueError for a bad option.)");
}

}  // namespace rayform::python
