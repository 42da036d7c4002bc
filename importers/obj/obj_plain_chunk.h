// A plain chunk of OBJ text (ChunkScan::plain: only `v`, `vn`, `vt` and
// `f` lines, comments and lines tinyobjloader ignores) parsed by
// tinyobj::LoadObjWithCallback into what tinyobj::LoadObj (triangulate =
// false) gives for it behind its state lines: the same floats (the same
// number parser) and faces, without LoadObj's per-face vectors and shape
// export (about a third of its time on a large mesh: docs/performance.md).
// Where every number comes before the first face and every corner is a
// plain decimal (ChunkScan::faces_read_from), tinyobjloader reads the lines
// before that face and the faces are read here: an index of 1 to 9 digits
// without sign or leading zero is what tinyobjloader's atoi makes of it,
// and the face lines were two thirds of the callback parse's time.
#pragma once

#include "rayform/importers/obj/obj_chunk_scan.h"
#include "rayform/importers/obj/obj_parse_bytes.h"

#include <tiny_obj_loader.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace rayform::obj {

// What LoadObj gives every face of a plain chunk: its state lines decide it
// (the chunk holds none), and the shape its faces make takes its name.
struct FaceState {
  std::string shape_name;
  int material = -1;
  unsigned int smoothing_group = 0;
};

// Parses `body`, a chunk whose scan is `scan` (plain), into `r`: the
// positions, normals and uvs of its lines (no colours: its first `v` line
// has none, and LoadObj then keeps none), and one shape of its faces
// (polygons whole) with `state`, or none without faces. r->ok is false
// where a corner's position reads 0 (LoadObj fails there: the chunked parse
// falls back to it, for its message); r->warn stays empty (LoadObj warns
// only of index bounds there, which the chunked parse checks itself).
void parse_plain_chunk(std::string_view body, const ChunkScan& scan, const FaceState& state, ChunkParse* r);

// Where parse_plain_chunk_into writes a chunk's faces, all triangles: its
// place in the joined shape's arrays, `faces` long (3 faces corners).
struct TriangleTarget {
  tinyobj::index_t* corners = nullptr;
  unsigned char* face_corners = nullptr;
  int* materials = nullptr;
  unsigned int* smoothing_groups = nullptr;
  size_t faces = 0;
};

// As parse_plain_chunk, but the faces are written to `to` (r->shapes stays
// empty): r->ok also needs exactly to.faces faces, each of three corners
// (nothing is written past them).
void parse_plain_chunk_into(std::string_view body, const ChunkScan& scan, const FaceState& state,
                            const TriangleTarget& to, ChunkParse* r);

}  // namespace rayform::obj
