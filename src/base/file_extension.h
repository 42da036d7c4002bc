// A file's extension as the readers and writers dispatch on it.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace rayform {

// The extension with its dot, lower-cased ("a/B.PNG" -> ".png"); "" when none.
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace rayform
