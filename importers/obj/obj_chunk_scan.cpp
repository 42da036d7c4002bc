#include "rayform/importers/obj/obj_chunk_scan.h"

namespace rayform::obj {
namespace {

// A face line (after "f "): its number of corners, or 0 when it has a '-',
// a number of more than 9 digits (atoi could wrap it to a negative index) or
// more corners than LoadObj's unsigned char count of a face's corners holds.
// A corner is plain when it is i, i/j, i//k or i/j/k, each index a decimal
// from 1 of at most 9 digits without sign or leading zero. `plain` is
// cleared where a corner names a uv or normal and is not plain:
// tinyobjloader's raw triple gives 0 for a field that is not there and for
// one that reads 0, which LoadObj refuses (a position, always there, the
// callback parse checks itself). `simple` is cleared where any corner is
// not plain. One pass over each corner's characters.
int plain_face_corners(std::string_view s, bool& plain, bool& simple) {
  int corners = 0;
  const size_t n = s.size();
  for (size_t i = 0;; ++corners) {
    while (i < n && is_space(s[i])) ++i;
    if (i == n) break;
    bool slash = false, form = true;  // the corner names a uv or normal; is plain
    int fields = 1;                   // '/'-separated fields so far
    size_t digits = 0, run = 0;       // digits of the current field; consecutive digits
    for (; i < n && !is_space(s[i]); ++i) {
      const char c = s[i];
      if (c >= '0' && c <= '9') {
        if (++run > 9) return 0;
        if (digits++ == 0 && c == '0') form = false;  // a leading zero
      } else if (c == '/') {
        run = 0;
        slash = true;
        if (fields == 1 && digits == 0) form = false;  // no position
        if (++fields > 3) form = false;
        digits = 0;
      } else {
        if (c == '-') return 0;
        run = 0;
        form = false;
      }
    }
    if (digits == 0) form = false;  // the last field empty (the middle one of three may be)
    if (slash) plain = plain && form;
    simple = simple && form;
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

// What decides ChunkScan::faces_read_from, gathered line by line.
struct FaceLines {
  size_t first = ChunkScan::none;  // the first face line's offset in the chunk
  bool simple = true;              // every corner so far plain (plain_face_corners)
  bool numbers_after = false;      // a v, vt or vn line after the first face line
};

// Sorts one line (t: without its leading blanks; the chunk starts at
// `begin`) into `scan`; false where the chunk turned out unsupported.
bool scan_line(ChunkScan& scan, FaceLines& faces, size_t begin, const Line& line, std::string_view t) {
  auto at = [&](size_t i) { return i < t.size() ? t[i] : '\0'; };
  if (t.empty() || t[0] == '#') return true;
  if (is_vertex_line(t)) {
    if (scan.vertex_lines++ == 0 && numbers(t.substr(2)) >= 6) scan.plain = false;
    faces.numbers_after = faces.numbers_after || faces.first != ChunkScan::none;
    return true;
  }
  if (t[0] == 'v' && (at(1) == 'n' || at(1) == 't') && is_space(at(2))) {
    faces.numbers_after = faces.numbers_after || faces.first != ChunkScan::none;
    return true;
  }
  if ((t[0] == 'v' && at(1) == 'w' && is_space(at(2))) || ((t[0] == 'l' || t[0] == 'p') && is_space(at(1)))) {
    scan.supported = false;  // skin weights, lines, points
  } else if (t[0] == 'f' && is_space(at(1))) {
    if (faces.first == ChunkScan::none) faces.first = line.at - begin;
    const int corners = plain_face_corners(t.substr(2), scan.plain, faces.simple);
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
}

}  // namespace

// One pass over the chunk: each line's end is found together with the bytes
// that make it unsupported (a '\0', or a lone '\r', which ends a line too
// in tinyobjloader).
ChunkScan scan_chunk(std::string_view text, size_t begin, size_t end) {
  ChunkScan scan;
  FaceLines faces;
  const char* data = text.data();
  for (size_t p = begin; p < end;) {
    const size_t q = find_first_byte<'\n', '\r', '\0'>(data, p, end);
    size_t next = q < end ? q + 1 : end;
    if (q < end && data[q] != '\n') {
      if (data[q] != '\r' || q + 1 == end || data[q + 1] != '\n') {
        ChunkScan unsupported;
        unsupported.supported = false;
        return unsupported;
      }
      next = q + 2;  // "\r\n"
    }
    const Line line{text.substr(p, q - p), p};
    if (!scan_line(scan, faces, begin, line, without_leading_blanks(line.text))) return scan;
    p = next;
  }
  if (scan.plain && faces.simple && !faces.numbers_after) scan.faces_read_from = faces.first;
  return scan;
}

}  // namespace rayform::obj
