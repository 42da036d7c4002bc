// Reader of the MIT 6.837 ray-casting scene format (.txt), both dialects (see
// docs/course-format.md). Fills a Scene; every error names file:line:column
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
  // The dialect to use; when unset it is 2019 if the scene uses `falloff` or
  // `bump`, else 2012.
  std::optional<CourseDialect> dialect;
  FileAccess access{};  // meshes and textures the scene names
};

struct CourseScene {
  Scene scene;
  CourseDialect dialect = CourseDialect::v2012;
  std::vector<std::string> warnings;
};

// Reads a scene file. Relative mesh and texture paths resolve against the
// scene file's folder, then (not under FileAccess::confine) the working
// directory. Throws rayform::Error.
CourseScene read_course_scene(const std::string& path, const CourseReadOptions& options = {});

// Parses scene text; `path` names it in messages and anchors relative paths.
CourseScene parse_course_scene(std::string_view text, const std::string& path, const CourseReadOptions& options = {});

}  // namespace rayform
