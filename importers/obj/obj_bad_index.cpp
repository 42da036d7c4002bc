#include "rayform/importers/obj/obj_bad_index.h"

#include <cstdlib>
#include <sstream>

namespace rayform::obj {

bool find_bad_index(const std::string& text, int kind, BadIndex* bad) {
  std::istringstream in(text);
  std::string line;
  size_t counts[3] = {0, 0, 0};
  size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    size_t b = line.find_first_not_of(" \t");
    if (b == std::string::npos) continue;
    const char* t = line.c_str() + b;
    if (t[0] == 'v' && (t[1] == ' ' || t[1] == '\t')) counts[0]++;
    else if (t[0] == 'v' && t[1] == 't' && (t[2] == ' ' || t[2] == '\t')) counts[1]++;
    else if (t[0] == 'v' && t[1] == 'n' && (t[2] == ' ' || t[2] == '\t')) counts[2]++;
    else if (t[0] == 'f' && (t[1] == ' ' || t[1] == '\t')) {
      std::istringstream fs_(std::string(t + 2));
      std::string corner;
      while (fs_ >> corner) {
        // corner: v, v/t, v//n, v/t/n
        std::string parts[3];
        size_t s1 = corner.find('/');
        parts[0] = corner.substr(0, s1);
        if (s1 != std::string::npos) {
          size_t s2 = corner.find('/', s1 + 1);
          parts[1] = corner.substr(s1 + 1, s2 == std::string::npos ? std::string::npos : s2 - s1 - 1);
          if (s2 != std::string::npos) parts[2] = corner.substr(s2 + 1);
        }
        if (parts[kind].empty()) continue;
        long i = std::strtol(parts[kind].c_str(), nullptr, 10);
        long n = long(counts[kind]);
        bool ok = (i > 0 && i <= n) || (i < 0 && n + i >= 0);
        if (!ok) {
          *bad = BadIndex{line_no, i, counts[kind]};
          return true;
        }
      }
    }
  }
  return false;
}

}  // namespace rayform::obj
