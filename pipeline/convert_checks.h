// The checks of a conversion's arguments, made before the input is read, and
// the dialect it writes: one owner for `rayform convert`
// (cli/convert_command.cpp) and rayform.convert (python/file_calls.cpp). A
// check returns an empty string when the argument is good, else the problem,
// which each front end puts under its own argument name.
#pragma once

#include "rayform/importers/scene_io.h"

#include <optional>
#include <string>

namespace rayform {

// The longitudes of a tessellated sphere a conversion accepts (SaveOptions::sphere_segments).
inline constexpr int min_sphere_segments = 3;
inline constexpr int max_sphere_segments = 4096;

// `output` as the scene written from `input`: empty, or "OUTPUT: the output
// is the input file; choose another name", or the unknown extension's
// message (scene_format_from_path).
std::string convert_output_problem(const std::string& input, const std::string& output);

// `dir` as the folder of the side files of `output` (SaveOptions::side_folder;
// `embed`: SaveOptions::embed, spelled `embed_name` by the front end): empty,
// or why it cannot be (a folder that does not exist, an output that has no
// side files, a course file that cannot name them).
std::string side_folder_problem(const std::string& output, const std::string& dir, bool embed,
                                const std::string& embed_name);

// The course dialect a conversion writes: `asked`, else the one a course
// input was read in (none for other inputs: the writer's choice).
std::optional<CourseDialect> convert_dialect(std::optional<CourseDialect> asked, const LoadedScene& input);

}  // namespace rayform
