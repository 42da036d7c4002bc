#include "rayform/importers/text_format.h"

#include <charconv>
#include <cstdint>
#include <cstdio>

namespace rayform {

std::string format_float(float v) {
  if (v == 0.f) return "0";  // also -0
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string format_vec3(vec3 v) { return format_float(v.x) + " " + format_float(v.y) + " " + format_float(v.z); }

std::string quoted_list(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& x : names) out += (out.empty() ? "'" : ", '") + x + "'";
  return out;
}

std::string safe_file_name(const std::string& name) {
  std::string out;
  for (char c : name) {
    bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    out += ok ? c : '_';
  }
  while (!out.empty() && out[0] == '.') out[0] = '_';  // no hidden files
  if (out.size() > max_safe_file_name) {
    // The start, and a hash of the whole name (FNV-1a, 32 bits) that keeps
    // names apart which differ only past the cut.
    uint32_t h = 2166136261u;
    for (char c : name) h = (h ^ uint8_t(c)) * 16777619u;
    char hex[16];
    std::snprintf(hex, sizeof hex, "_%08x", unsigned(h));
    out = out.substr(0, max_safe_file_name - 9) + hex;
  }
  return out.empty() ? std::string("unnamed") : out;
}

}  // namespace rayform
