#include "rayform/importers/referenced_files.h"

#include <cctype>

namespace rayform {
namespace fs = std::filesystem;

bool has_uri_scheme(const std::string& name) {
  // RFC 3986: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"; one letter is a drive.
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  size_t i = 1;
  while (i < name.size() &&
         (std::isalnum(static_cast<unsigned char>(name[i])) || name[i] == '+' || name[i] == '-' || name[i] == '.'))
    ++i;
  return i < name.size() && name[i] == ':' && i > 1;
}

namespace {
// Whether `path` is `folder` or lies below it (both canonical).
bool lies_within(const fs::path& path, const fs::path& folder) {
  auto p = path.begin(), f = folder.begin();
  for (; f != folder.end(); ++f, ++p)
    if (p == path.end() || *p != *f) return false;
  return true;
}
}  // namespace

bool lies_within_folder(const fs::path& path, const fs::path& folder) {
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  if (ec) return false;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return !ec && lies_within(p, f);
}

std::string referenced_file_problem(const std::string& scene_file, const std::string& what, const std::string& name,
                                    const fs::path& resolved, const FileAccess& access) {
  const std::string named = what + " '" + name + "'";
  std::error_code ec;
  if (access.confine) {
    if (has_uri_scheme(name) && name.rfind("data:", 0) != 0)
      return named + " is a URI; only data: URIs are read under --confine";
    if (fs::path(name).is_absolute() || (!name.empty() && (name[0] == '/' || name[0] == '\\')))
      return named + " is an absolute path, refused by --confine";
    if (!lies_within_folder(resolved, fs::absolute(scene_file, ec).parent_path()))
      return named + " lies outside the scene's folder " +
             fs::weakly_canonical(fs::absolute(scene_file, ec).parent_path(), ec).string() + " (refused by --confine)";
  }
  const fs::file_status status = fs::status(resolved, ec);
  if (!ec && fs::exists(status) && !fs::is_regular_file(status))
    return named + " (" + resolved.string() + ") is not a regular file";
  return "";
}

}  // namespace rayform
