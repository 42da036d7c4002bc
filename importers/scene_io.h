// One entry point over the format readers: picks the format by extension.
#pragma once

#include "course_txt/course_reader.h"
#include "gltf/gltf_reader.h"
#include "obj/obj_reader.h"
#include "scene/scene.h"

#include <optional>
#include <string>
#include <vector>

namespace rayform {

enum class SceneFormat { course_txt, obj, gltf };

struct LoadOptions {
  std::optional<CourseDialect> dialect;  // course scenes only (keep first: callers brace-initialise it)
  bool flat_normals = false;             // OBJ: normals missing from the file are faceted, not smooth
  int gltf_scene = -1;                   // glTF: the scene to load; -1: the file's default scene
  uint64_t max_texture_texels = default_max_texture_texels;  // glTF images (files: PrepareOptions::images)
};

struct LoadedScene {
  Scene scene;
  SceneFormat format = SceneFormat::course_txt;
  CourseDialect dialect = CourseDialect::v2012;  // course scenes: the dialect used
  std::vector<std::string> warnings;
  std::vector<ExtensionUse> extensions;  // glTF: the extensions the file names, and how each was used
};

// Throws rayform::Error for an unknown extension or a bad file.
SceneFormat scene_format_from_path(const std::string& path);
LoadedScene load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace rayform
