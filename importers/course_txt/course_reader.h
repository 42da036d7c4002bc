// Reader of the MIT 6.837 ray-casting scene format (.txt), all three dialects
// (2012, 2019, a5; see docs/course-format.md). Fills a Scene; every error names file:line:column
// and what was expected.
#pragma once

#include "rayform/importers/course_txt/course_dialect.h"
#include "rayform/importers/referenced_files.h"
#include "rayform/scene/scene.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rayform {

struct CourseReadOptions {
  // The dialect to use; when unset, detect_course_dialect's.
  std::optional<CourseDialect> dialect;
  FileAccess access{};  // meshes and textures the scene names
};

struct CourseScene {
  Scene scene;
  CourseDialect dialect = CourseDialect::v2012;
  std::vector<std::string> warnings;
};

// The dialect of a scene whose command line names none: a5 if its cubeMap
// folder holds .bmp faces or it uses `Noise` or `refractionIndex`, whether or
// not it also uses `falloff`; else 2019 if it uses `falloff` or `bump` or its
// cubeMap folder holds .png faces; else 2012. `path` (the scene file) anchors the cube map
// folder as the reader resolves it.
CourseDialect detect_course_dialect(std::string_view text, const std::string& path, const FileAccess& access = {});

// The file type of the cube map faces of a dialect: ".bmp" (a5) or ".png".
std::string cube_map_extension(CourseDialect dialect);

// The most octaves a Noise may have (2^octaves scales the point; beyond ~60 a
// double's exponent gives nothing more).
inline constexpr int max_noise_octaves = 64;

// Reads a scene file. Relative mesh and texture paths resolve against the
// scene file's folder, then (not under FileAccess::confine) the working
// directory. Throws rayform::Error.
CourseScene read_course_scene(const std::string& path, const CourseReadOptions& options = {});

// Parses scene text; `path` names it in messages and anchors relative paths.
CourseScene parse_course_scene(std::string_view text, const std::string& path, const CourseReadOptions& options = {});

}  // namespace rayform
