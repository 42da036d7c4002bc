#include "rayform/pipeline/convert_checks.h"

#include "rayform/base/error.h"
#include "rayform/base/file_extension.h"
#include "rayform/importers/course_txt/course_writer.h"

#include <filesystem>

namespace rayform {
namespace fs = std::filesystem;

std::string convert_output_problem(const std::string& input, const std::string& output) {
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(input, output, ec))
    return output + ": the output is the input file; choose another name";
  try {
    scene_format_from_path(output);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string side_folder_problem(const std::string& output, const std::string& dir, bool embed,
                                const std::string& embed_name) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return "folder '" + dir + "' does not exist";
  const std::string ext = lower_extension(output);
  if (ext == ".glb") return "a .glb holds everything in one file: there are no side files";
  if (ext == ".gltf" && embed) return "with " + embed_name + " the .gltf holds everything: there are no side files";
  if (ext == ".txt") return course_side_folder_problem(output, dir);
  return "";
}

std::optional<CourseDialect> convert_dialect(std::optional<CourseDialect> asked, const LoadedScene& input) {
  if (!asked && input.format == SceneFormat::course_txt) return input.dialect;
  return asked;
}

}  // namespace rayform
