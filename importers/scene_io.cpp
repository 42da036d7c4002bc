#include "scene_io.h"

#include "scene/error.h"
#include "scene/file_extension.h"

namespace rayform {

SceneFormat scene_format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".txt") return SceneFormat::course_txt;
  if (ext == ".obj") return SceneFormat::obj;
  if (ext == ".gltf" || ext == ".glb") return SceneFormat::gltf;
  throw Error(path + ": unknown scene format '" + ext + "': expected .txt (course), .obj, .gltf or .glb");
}

LoadedScene load_scene(const std::string& path, const LoadOptions& options) {
  LoadedScene out;
  out.format = scene_format_from_path(path);
  switch (out.format) {
    case SceneFormat::course_txt: {
      CourseScene cs = read_course_scene(path, CourseReadOptions{options.dialect});
      out.scene = std::move(cs.scene);
      out.dialect = cs.dialect;
      out.warnings = std::move(cs.warnings);
      return out;
    }
    case SceneFormat::obj:
      out.scene = read_obj_scene(path, ObjReadOptions{options.flat_normals}, &out.warnings);
      return out;
    case SceneFormat::gltf: {
      GltfReadOptions gltf;
      gltf.scene = options.gltf_scene;
      gltf.images.max_texels = options.max_texture_texels;
      out.scene = read_gltf_scene(path, gltf, &out.warnings, &out.extensions);
      return out;
    }
  }
  return out;
}

}  // namespace rayform
