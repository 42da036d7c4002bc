// Polygons of an OBJ parse split into triangles exactly as tinyobjloader
// splits them, for the chunked parse (obj_parallel_parse.h), which parses
// with LoadObj(triangulate = false) because a chunk does not hold the
// positions a polygon's split depends on.
//
// LoadObj(triangulate = true), in the Debian build (no earcut), splits
//   a quad a b c d along its shorter diagonal: (a b c) (a c d) when
//     |c - a|^2 < |d - b|^2 (squares summed in float, x + y + z), else
//     (a b d) (b c d);
//   a polygon of five or more corners by an ear-clipping loop of its own.
// Quads are split here by that rule. Larger polygons (rare in real files)
// are handed to tinyobjloader itself: a small OBJ text made of the `v` lines
// that declared their corners, copied from the file (so that the positions
// are the very same floats), one `vt` per corner to tell the corners apart
// afterwards, and the polygon as one face; its triangles are mapped back.
#pragma once

#include <tiny_obj_loader.h>

#include <functional>
#include <string_view>
#include <vector>

namespace rayform {

// The text of the `v` line that declared vertex `v` (0-based).
using VertexLineText = std::function<std::string_view(int v)>;

// Replaces every face of `mesh` with more than three corners by its
// triangles, each with the face's material and smoothing group, in face
// order. `positions` holds x, y, z of every vertex of the file; every corner's
// vertex index must be below positions.size() / 3. False where a polygon's
// split could not be made as LoadObj makes it (tinyobjloader failed or warned
// on the polygon's text): then parse the whole text with LoadObj.
bool split_polygons_like_loadobj(tinyobj::mesh_t* mesh, const std::vector<tinyobj::real_t>& positions,
                                 const VertexLineText& vertex_line);

}  // namespace rayform
