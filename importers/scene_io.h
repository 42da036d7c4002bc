// One entry point over the format readers: picks the format by extension.
#pragma once

#include "rayform/importers/course_txt/course_reader.h"
#include "rayform/importers/gltf/gltf_reader.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/referenced_files.h"
#include "rayform/base/limits.h"
#include "rayform/scene/scene.h"
#include "rayform/base/work_share.h"

#include <optional>
#include <string>
#include <vector>

namespace rayform {

enum class SceneFormat { course_txt, obj, gltf };

struct LoadOptions {
  std::optional<CourseDialect> dialect;  // course scenes only (keep first: callers brace-initialise it)
  bool flat_normals = false;             // OBJ: normals missing from the file are faceted, not smooth
  int gltf_scene = -1;                   // glTF: the scene to load; -1: the file's default scene
  Limits limits{};                       // checked while reading and, for the totals, after
  FileAccess access{};                   // the files a scene names
  // The processes loading the same file at once, to share the work among
  // (see ObjReadOptions::share): OBJ only, where parsing a large text pays
  // to share; course scenes and glTF files are read whole by each.
  const WorkShare* share = nullptr;
};

struct LoadedScene {
  Scene scene;
  SceneFormat format = SceneFormat::course_txt;
  CourseDialect dialect = CourseDialect::v2012;  // course scenes: the dialect used
  std::vector<std::string> warnings;
  std::vector<ExtensionUse> extensions;  // glTF: the extensions the file names, and how each was used
};

// Throws rayform::Error for an unknown extension, a bad file, or a scene
// beyond options.limits (triangles and vertices of all meshes).
SceneFormat scene_format_from_path(const std::string& path);
LoadedScene load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace rayform
