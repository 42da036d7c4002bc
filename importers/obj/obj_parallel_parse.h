// An OBJ text parsed by tinyobjloader in chunks at once, with exactly the
// result of one tinyobj::LoadObj(triangulate = true, default_vcols_fallback =
// false) over the whole text, or not at all.
//
// The text is cut at line ends into chunks; a quick scan of each chunk
// (obj_chunk_scan.h: line kinds only, no numbers) finds the state lines
// (mtllib, usemtl, g, o, s), the `v` lines and what the stitching cannot
// reproduce. Each chunk is then parsed by LoadObj, its polygons left whole,
// behind copies of the state lines in force at its start (the first mtllib,
// the last usemtl, g/o and s before it, in file order), so that its faces get
// the material, smoothing group and shape name the whole-file parse gives
// them; positive face indices are absolute already. A plain chunk (vertex
// and face lines alone) is parsed by LoadObjWithCallback instead, its faces
// given what LoadObj gives a face behind those state lines
// (obj_plain_chunk.h). The chunks' vertex arrays are concatenated,
// the polygons split into triangles as LoadObj splits them
// (obj_polygon_split.h: that needs the positions of their corners, which
// another chunk may hold), and the shapes joined where a `g`/`o` section runs
// across a chunk end.
//
// Falls back (returns false) where that would not be exact: negative
// (relative) indices, lines, points, tags and skin weights, a lone '\r' line
// end or a NUL byte, faces with fewer than three corners or more than 255, a
// face index past the last vertex, a polygon naming a vertex declared after
// it (LoadObj splits a polygon by the vertices read when its group ends),
// any parse error, and any tinyobjloader warning other than an unknown
// material (warnings carry line numbers or depend on the order of a whole
// file).
#pragma once

#include "rayform/base/work_share.h"

#include <tiny_obj_loader.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rayform {

// What tinyobj::LoadObj gives (its materials aside: see ObjReader).
struct ObjParse {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::string warn;
};

// A fresh material reader per LoadObj call (each one is asked at its first mtllib).
using MaterialReaderFactory = std::function<std::unique_ptr<tinyobj::MaterialReader>()>;

// Parses `text` in chunks of about `chunk_bytes` (at least one line each) at
// once. False, with `out` unspecified, where the result could differ from one
// LoadObj over the whole text: then parse it that way.
//
// With a `share` of several parts (rayform/base/work_share.h), every part
// calls this with the same text, readers and chunk size; each scans and
// parses only the chunks that fall to it (every parts-th one). A first
// exchange gives every part every chunk's scan (obj_chunk_scan.h), from
// which each knows the state lines in force at its chunks and whether all
// return false (then before any parse); a second one every chunk's result
// (obj_parse_bytes.h), from which each joins the same ObjParse as without a
// share, or returns false alike. Throws rayform::Error on every part when a
// chunk's scan or parse threw on one.
bool parse_obj_chunked(std::string_view text, const MaterialReaderFactory& readers, size_t chunk_bytes, ObjParse* out,
                       const WorkShare* share = nullptr);

}  // namespace rayform
