#include "rayform/importers/gltf/gltf_messages.h"

#include <sstream>

namespace rayform {

std::string gltf_path(const char* array, long i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

std::string gltf_one_line(const std::string& text) {
  constexpr const char* blanks = " \t\r\n";
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) {
    const size_t first = line.find_first_not_of(blanks);
    if (first == std::string::npos) continue;
    line = line.substr(first, line.find_last_not_of(blanks) - first + 1);
    out += (out.empty() ? "" : "; ") + line;
  }
  return out;
}

}  // namespace rayform
