// The quick scan of a chunk of OBJ text that the chunked parse makes before
// parsing it (obj_parallel_parse.h): line kinds only, no numbers. It finds
// the state lines (mtllib, usemtl, g, o, s) that the chunks after it need in
// front of their text, counts the `v` lines and the faces of each g/o
// section, and tells whether the chunk holds anything the stitching of
// chunks cannot reproduce (then the whole text is parsed in one piece).
#pragma once

#include "rayform/importers/obj/obj_line_bytes.h"

#include <cstddef>
#include <string_view>
#include <vector>

namespace rayform::obj {

// A line of the text (without its line end) and where it starts.
struct Line {
  std::string_view text;
  size_t at = 0;
  bool empty() const { return text.empty(); }
};

// What the scan of one chunk found.
struct ChunkScan {
  bool supported = true;
  Line first_mtllib, last_usemtl, last_group, last_smoothing;
  std::vector<size_t> section_faces{0};  // faces before the chunk's first g/o line, then after each
  size_t vertex_lines = 0;               // `v` lines
  // Per face of more than three corners, in order: the chunk's `v` lines before it.
  std::vector<size_t> polygon_vertices_before;
  // Whether tinyobjloader's callback parse gives exactly what LoadObj gives
  // for the chunk (obj_plain_chunk.h), where every corner names a position
  // from 1: no state line (mtllib, usemtl, g, o, s), every corner that names
  // a uv or normal of the form i, i/j, i//k or i/j/k (each index a decimal
  // from 1 of at most 9 digits, without sign or leading zero), and no colour
  // on its first `v` line (fewer than six numbers: then LoadObj keeps no
  // colour of the chunk).
  bool plain = true;
  // Where the faces of a plain chunk may be read without tinyobjloader
  // (obj_plain_chunk.h): the offset in the chunk of its first face line,
  // where every corner of every face is i, i/j, i//k or i/j/k (as above,
  // the position's index too) and no `v`, `vt` or `vn` line comes after
  // that line; else `none` (also where the chunk has no face).
  static constexpr size_t none = size_t(-1);
  size_t faces_read_from = none;
};

// Calls visit(line, t) for each line of [begin, end) (its '\r\n' or '\n'
// end taken off), t being the line without its leading blanks, as LoadObj
// reads it, until visit returns false.
template <class Visit>
inline void for_each_line(std::string_view text, size_t begin, size_t end, Visit visit) {
  for (size_t p = begin; p < end;) {
    const size_t line_end = find_first_byte<'\n'>(text.data(), p, end);
    size_t e = line_end;
    if (e > p && text[e - 1] == '\r') --e;
    const Line line{text.substr(p, e - p), p};
    p = line_end < end ? line_end + 1 : end;
    if (!visit(line, without_leading_blanks(line.text))) return;
  }
}

inline bool is_vertex_line(std::string_view t) { return t.size() > 1 && t[0] == 'v' && is_space(t[1]); }

// Sorts each line of [begin, end) of `text` by the tests LoadObj makes, in its order.
ChunkScan scan_chunk(std::string_view text, size_t begin, size_t end);

}  // namespace rayform::obj
