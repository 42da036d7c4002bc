#include "rayform/importers/scene_writer.h"

#include "rayform/importers/course_txt/course_writer.h"
#include "rayform/importers/gltf/gltf_writer.h"
#include "rayform/importers/obj/obj_writer.h"
#include "rayform/base/error.h"
#include "rayform/base/file_extension.h"
#include "rayform/importers/scene_flatten.h"

#include <filesystem>
#include <system_error>

namespace rayform {
namespace fs = std::filesystem;

// ---- entry point ------------------------------------------------------------------

SaveResult save_scene(const Scene& scene, const std::string& path, const SaveOptions& options,
                      std::vector<std::string>* messages) {
  const std::string ext = lower_extension(path);
  if (ext != ".txt" && ext != ".obj" && ext != ".gltf" && ext != ".glb")
    throw Error(path + ": cannot write scenes of type '" + ext + "': expected .txt (course), .obj, .gltf or .glb");
  if (options.sphere_segments < 3)
    throw Error(path + ": sphere segments must be at least 3, got " + std::to_string(options.sphere_segments));
  fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw Error(path + ": cannot write: folder '" + dir.string() + "' does not exist");
  if (fs::is_directory(path, ec)) throw Error(path + ": cannot write: it is a folder");
  if (!options.side_folder.empty() && !fs::is_directory(options.side_folder, ec))
    throw Error(path + ": cannot write: folder '" + options.side_folder + "' for its side files does not exist");
  if (scene.root == invalid) throw Error(path + ": the scene has no root node: nothing to write");

  const std::string name = fs::path(path).filename().string();
  Scene flat;
  const Scene* s = &scene;
  if (options.flatten) {
    flat = flatten_scene(scene, options.sphere_segments, name, messages);
    s = &flat;
  }
  if (ext == ".txt") {
    CourseWriteOptions o;
    o.dialect = options.dialect;
    o.side_folder = options.side_folder;
    return write_course_scene(*s, path, o, messages);
  }
  if (ext == ".obj") {
    ObjWriteOptions o;
    o.sphere_segments = options.sphere_segments;
    o.flattened = options.flatten;
    o.side_folder = options.side_folder;
    return write_obj_scene(*s, path, o, messages);
  }
  GltfWriteOptions o;
  o.binary = ext == ".glb";
  o.embed = options.embed;
  o.sphere_segments = options.sphere_segments;
  o.shape_extras = options.shape_extras;
  o.side_folder = options.side_folder;
  return write_gltf_scene(*s, path, o, messages);
}

void protect_scene_inputs(const Scene& scene, OutputFiles& out) {
  out.protect(scene.source_path);
  for (const Mesh& m : scene.meshes) out.protect(m.source_path);
  for (const Texture& t : scene.textures) out.protect(t.path);
}

void require_scene_root(const Scene& scene, const std::string& path) {
  if (scene.root == invalid || size_t(scene.root) >= scene.nodes.size())
    throw Error(path + ": the scene has no root node: nothing to write");
}

}  // namespace rayform
