#include "rayform/importers/obj/obj_chunk_scan.h"

namespace rayform::obj {
namespace {

// Whether a face corner is i, i/j, i//k or i/j/k, each index a decimal from
// 1 of at most 9 digits without sign or leading zero.
bool plain_corner(std::string_view c) {
  size_t i = 0;
  auto index = [&] {
    const size_t start = i;
    if (i < c.size() && c[i] >= '1' && c[i] <= '9')
      for (++i; i < c.size() && i - start < 9 && c[i] >= '0' && c[i] <= '9';) ++i;
    return i > start && (i == c.size() || c[i] == '/');
  };
  if (!index()) return false;
  if (i == c.size()) return true;
  ++i;                                   // the '/'
  if (i < c.size() && c[i] == '/') ++i;  // i//k
  else if (!index()) return false;       // i/j
  else if (i == c.size()) return true;
  else ++i;  // i/j/k
  return index() && i == c.size();
}

// A face line (after "f "): its number of corners, or 0 when it has a '-',
// a number of more than 9 digits (atoi could wrap it to a negative index) or
// more corners than LoadObj's unsigned char count of a face's corners holds.
// `plain` is cleared where a corner names a uv or normal and is not
// plain_corner: tinyobjloader's raw triple gives 0 for a field that is not
// there and for one that reads 0, which LoadObj refuses (a position, always
// there, the callback parse checks itself).
int plain_face_corners(std::string_view s, bool& plain) {
  if (s.find('-') != std::string_view::npos) return 0;
  int corners = 0;
  const size_t n = s.size();
  for (size_t i = 0;; ++corners) {
    while (i < n && is_space(s[i])) ++i;
    if (i == n) break;
    const size_t start = i;
    bool slash = false;  // the corner names a uv or normal
    for (; i < n && !is_space(s[i]); ++i) slash |= s[i] == '/';
    if (slash && plain) plain = plain_corner(s.substr(start, i - start));
    if (i - start < 10) continue;
    for (size_t k = start, digits = 0; k < i; ++k) {
      digits = s[k] >= '0' && s[k] <= '9' ? digits + 1 : 0;
      if (digits > 9) return 0;
    }
  }
  return corners <= 255 ? corners : 0;
}

// The blank-separated words of a line's rest (after "v ").
size_t numbers(std::string_view s) {
  size_t words = 0;
  for (size_t i = 0; i < s.size();) {
    while (i < s.size() && is_space(s[i])) ++i;
    if (i == s.size()) break;
    ++words;
    while (i < s.size() && !is_space(s[i])) ++i;
  }
  return words;
}

}  // namespace

ChunkScan scan_chunk(std::string_view text, size_t begin, size_t end) {
  ChunkScan scan;
  const std::string_view chunk = text.substr(begin, end - begin);
  if (chunk.find('\0') != std::string_view::npos) scan.supported = false;
  for (size_t r = chunk.find('\r'); scan.supported && r != std::string_view::npos; r = chunk.find('\r', r + 1))
    if (r + 1 == chunk.size() || chunk[r + 1] != '\n') scan.supported = false;  // a lone '\r' ends a line too
  if (!scan.supported) return scan;
  for_each_line(text, begin, end, [&](const Line& line, std::string_view t) {
    auto at = [&](size_t i) { return i < t.size() ? t[i] : '\0'; };
    if (t.empty() || t[0] == '#') return true;
    if (is_vertex_line(t)) {
      if (scan.vertex_lines++ == 0 && numbers(t.substr(2)) >= 6) scan.plain = false;
      return true;
    }
    if (t[0] == 'v' && (at(1) == 'n' || at(1) == 't') && is_space(at(2))) return true;
    if ((t[0] == 'v' && at(1) == 'w' && is_space(at(2))) || ((t[0] == 'l' || t[0] == 'p') && is_space(at(1)))) {
      scan.supported = false;  // skin weights, lines, points
    } else if (t[0] == 'f' && is_space(at(1))) {
      const int corners = plain_face_corners(t.substr(2), scan.plain);
      if (corners < 3) scan.supported = false;
      if (corners > 3) scan.polygon_vertices_before.push_back(scan.vertex_lines);
      ++scan.section_faces.back();
    } else if (t.compare(0, 6, "usemtl") == 0) {
      scan.last_usemtl = line;
      scan.plain = false;
    } else if (t.compare(0, 6, "mtllib") == 0 && is_space(at(6))) {
      if (scan.first_mtllib.empty()) scan.first_mtllib = line;
      scan.plain = false;
    } else if ((t[0] == 'g' || t[0] == 'o') && is_space(at(1))) {
      scan.last_group = line;
      scan.section_faces.push_back(0);
      scan.plain = false;
    } else if (t[0] == 't' && is_space(at(1))) {
      scan.supported = false;  // tags
    } else if (t[0] == 's' && is_space(at(1))) {
      scan.last_smoothing = line;
      scan.plain = false;
    }
    return scan.supported;
  });
  return scan;
}

}  // namespace rayform::obj
