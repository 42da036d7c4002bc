#include "rayform/importers/obj/obj_side_files.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace rayform::obj {
namespace fs = std::filesystem;
namespace {

bool ends_with_ci(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

}  // namespace

fs::path portable_path(std::string name) {
  std::replace(name.begin(), name.end(), '\\', '/');
  return fs::path(name).lexically_normal();
}

Resolved resolve_beside(const fs::path& dir, const std::string& name) {
  Resolved r;
  fs::path p = portable_path(name);
  if (p.empty()) return r;
  std::error_code ec;
  fs::path as_written = p.is_absolute() ? p : dir / p;
  if (fs::is_regular_file(as_written, ec)) {
    r.path = as_written;
    r.found = true;
    return r;
  }
  fs::path by_name = dir / p.filename();
  if (!p.filename().empty() && fs::is_regular_file(by_name, ec)) {
    r.path = by_name;
    r.found = true;
    r.by_name_only = true;
  }
  return r;
}

std::vector<std::string> split_mtllib(const std::string& rest, const fs::path& dir) {
  if (resolve_beside(dir, rest).found) return {rest};
  std::vector<std::string> out;
  std::istringstream ss(rest);
  std::string token, pending;
  while (ss >> token) {
    pending = pending.empty() ? token : pending + " " + token;
    if (ends_with_ci(pending, ".mtl")) {
      out.push_back(pending);
      pending.clear();
    }
  }
  if (!pending.empty()) out.push_back(pending);
  return out;
}

}  // namespace rayform::obj
