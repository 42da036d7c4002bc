#include "output_names.h"

#include "course_args.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace rayform::cli {

std::string safe_stem(const std::string& input) {
  std::string stem = std::filesystem::path(input).stem().string();
  // "", "." and ".." would name the folder itself or its parent ("...txt"
  // has the stem ".."): each dot becomes '_'; so does a separator.
  if (stem.find_first_not_of('.') == std::string::npos) return std::string(std::max<size_t>(stem.size(), 1), '_');
  for (char& c : stem)
    if (c == '/' || c == '\\') c = '_';
  return stem;
}

bool has_placeholder(const std::string& pattern, const std::string& name) {
  return pattern.find("{" + name + "}") != std::string::npos;
}

std::string expand_output_name(const std::string& pattern, const std::string& input, int frame,
                               const std::string& option) {
  std::string out;
  for (size_t i = 0; i < pattern.size();) {
    if (pattern[i] != '{') {
      out += pattern[i++];
      continue;
    }
    const size_t close = pattern.find('}', i);
    if (close == std::string::npos)
      throw UsageError(option + " '" + pattern + "': '{' without '}' (placeholders: {stem}, {frame})");
    const std::string name = pattern.substr(i + 1, close - i - 1);
    if (name == "stem") {
      out += safe_stem(input);
    } else if (name == "frame") {
      char digits[16];
      std::snprintf(digits, sizeof digits, "%04d", frame);
      out += digits;
    } else {
      throw UsageError(option + " '" + pattern + "': unknown placeholder {" + name +
                       "} (placeholders: {stem}, {frame})");
    }
    i = close + 1;
  }
  return out;
}

}  // namespace rayform::cli
