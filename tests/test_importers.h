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

// "path:line:column" of the `occurrence`-th (1-based) `needle` in `text`,
// counted independently of the readers: lines and columns from 1, a column per byte.
inline std::string where(const std::string& text, const std::string& needle, int occurrence = 1,
                         const std::string& path = "t.txt") {
  size_t pos = std::string::npos, from = 0;
  for (int i = 0; i < occurrence; ++i) {
    pos = text.find(needle, from);
    if (pos == std::string::npos) return "<'" + needle + "' not in the text>";
    from = pos + 1;
  }
  int line = 1, col = 1;
  for (size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return path + ":" + std::to_string(line) + ":" + std::to_string(col);
}

}  // namespace rayform::test
