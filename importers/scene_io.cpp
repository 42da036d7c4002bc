#include "rayform/importers/scene_io.h"

#include "rayform/base/error.h"
#include "rayform/base/file_extension.h"

#include <filesystem>
#include <system_error>

namespace rayform {

SceneFormat scene_format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".txt") return SceneFormat::course_txt;
  if (ext == ".obj") return SceneFormat::obj;
  if (ext == ".gltf" || ext == ".glb") return SceneFormat::gltf;
  throw Error(path + ": unknown scene format '" + ext + "': expected .txt (course), .obj, .gltf or .glb");
}

namespace {
// The one message of every command (render, info, convert, the course line)
// for a scene file that is missing or a folder.
void check_scene_file(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(st)) throw Error(path + ": cannot open scene file: no such file");
  if (std::filesystem::is_directory(st)) throw Error(path + ": cannot open scene file: it is a folder");
}

LoadedScene read_scene(const std::string& path, const LoadOptions& options) {
  LoadedScene out;
  out.format = scene_format_from_path(path);
  check_scene_file(path);
  switch (out.format) {
    case SceneFormat::course_txt: {
      CourseScene cs = read_course_scene(path, CourseReadOptions{options.dialect, options.access});
      out.scene = std::move(cs.scene);
      out.dialect = cs.dialect;
      out.warnings = std::move(cs.warnings);
      return out;
    }
    case SceneFormat::obj: {
      ObjReadOptions obj;
      obj.flat = options.flat_normals;
      obj.access = options.access;
      obj.share = options.share;
      out.scene = read_obj_scene(path, obj, &out.warnings);
      return out;
    }
    case SceneFormat::gltf: {
      GltfReadOptions gltf;
      gltf.scene = options.gltf_scene;
      gltf.limits = options.limits;
      gltf.access = options.access;
      out.scene = read_gltf_scene(path, gltf, &out.warnings, &out.extensions);
      return out;
    }
  }
  return out;
}
}  // namespace

LoadedScene load_scene(const std::string& path, const LoadOptions& options) {
  LoadedScene out = read_scene(path, options);
  uint64_t triangles = out.scene.triangles.size(), vertices = 3 * out.scene.triangles.size();
  for (const Mesh& m : out.scene.meshes) {
    triangles += m.triangle_count();
    vertices += m.positions.size();
  }
  if (triangles > options.limits.triangles)
    throw Error(path + ": " + limit_exceeded("triangles", triangles, options.limits.triangles));
  if (vertices > options.limits.vertices)
    throw Error(path + ": " + limit_exceeded("vertices", vertices, options.limits.vertices));
  return out;
}

}  // namespace rayform
