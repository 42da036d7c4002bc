// The files an OBJ names (its mtllib lines; the textures of its .mtl): how a
// name written in the file is found on disk.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rayform::obj {

// Names written on Windows ('\' separators, ".\x.jpg") as a portable path.
std::filesystem::path portable_path(std::string name);

// A file named inside another file: relative to that file's folder (or
// absolute) as written; failing that, its bare name in that folder (files
// are often moved next to the model while the names keep an old layout).
struct Resolved {
  std::filesystem::path path;
  bool found = false;
  bool by_name_only = false;
};
Resolved resolve_beside(const std::filesystem::path& dir, const std::string& name);

// The files an `mtllib` line names. The line may name several files, and a
// name may contain spaces ("mtllib box mtllib.mtl"): the whole rest of the
// line is tried first, then names split at whitespace and re-joined up to
// each ".mtl".
std::vector<std::string> split_mtllib(const std::string& rest, const std::filesystem::path& dir);

// `s` without its leading and trailing blanks (spaces, tabs, line ends).
inline std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const size_t e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

}  // namespace rayform::obj
