// Helpers shared by the importer tests.
#pragma once

#include "test_paths.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace rayform::test {

// A file of the third-party sample assets in RAYFORM_SHARED.
inline std::filesystem::path asset(const std::string& rel) { return shared_dir() / "assets" / rel; }

// Whether any of `v` (warnings, say) contains `s`.
inline bool any_contains(const std::vector<std::string>& v, const std::string& s) {
  return std::any_of(v.begin(), v.end(), [&](const std::string& w) { return w.find(s) != std::string::npos; });
}

}  // namespace rayform::test
