#include "rayform/base/plugin_library.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace rayform {
namespace fs = std::filesystem;

void* open_plugin(const char* file_name, const char* env_var, std::string* failure) {
  std::vector<fs::path> candidates;
  const char* named = std::getenv(env_var);
  if (named && *named) candidates.push_back(named);  // the one place looked at
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (candidates.empty() && !ec) {
    candidates.push_back(exe.parent_path() / file_name);
    candidates.push_back(exe.parent_path() / "../lib/rayform" / file_name);
  }
  // Compiled in (src/CMakeLists.txt): the install folder, then the build's.
  if (!named || !*named) {
#ifdef RAYFORM_PLUGIN_INSTALL_DIR
    candidates.push_back(fs::path(RAYFORM_PLUGIN_INSTALL_DIR) / file_name);
#endif
#ifdef RAYFORM_PLUGIN_DIR
    candidates.push_back(fs::path(RAYFORM_PLUGIN_DIR) / file_name);
#endif
  }
  std::string tried, error;
  for (const fs::path& c : candidates) {
    if (!fs::exists(c, ec)) {
      tried.append(" ").append(c.string());
      continue;
    }
    if (void* handle = dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
    error = dlerror();
  }
  *failure = !error.empty() ? error
                            : std::string(file_name)
                                  .append(" not found (looked at")
                                  .append(tried)
                                  .append("; set ")
                                  .append(env_var)
                                  .append(")");
  return nullptr;
}

}  // namespace rayform
