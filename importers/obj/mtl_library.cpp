#include "rayform/importers/obj/mtl_library.h"

#include <sstream>

namespace rayform::obj {

std::map<std::string, std::set<std::string>> mtl_keywords(const std::string& text) {
  std::map<std::string, std::set<std::string>> out;
  std::istringstream in(text);
  std::string line, current;
  while (std::getline(in, line)) {
    size_t e = line.find_last_not_of(" \t\r");
    line = e == std::string::npos ? std::string() : line.substr(0, e + 1);
    size_t b = line.find_first_not_of(" \t");
    if (b == std::string::npos) continue;
    std::string t = line.substr(b);
    if (t.size() > 7 && t.compare(0, 6, "newmtl") == 0 && (t[6] == ' ' || t[6] == '\t')) {
      current = t.substr(7);
      continue;
    }
    const size_t end = t.find_first_of(" \t");
    if (end != std::string::npos) out[current].insert(t.substr(0, end));  // a statement with a value
  }
  return out;
}

}  // namespace rayform::obj
