// The smooth normals the OBJ reader generates where a corner has none: per
// position, the sum of the unit normals of the triangles around it, each
// weighted by the triangle's angle at that corner (Thuermer & Wuethrich, so
// that the result does not depend on how a polygon was split), added in face
// order. The reader normalises the sums per vertex.
//
// Shared among the parts of a WorkShare (rayform/base/work_share.h), each
// part sums the positions of its range only (position ranges of equal size,
// in part order: the faces that touch a range are weighed by its part), and
// one exchange gives every part every range's sums: the same floats, bit for
// bit, as the sums made alone, since each position's sum is made alike, in
// face order. What throws on a part (an allocation) travels as its message,
// and every part then throws rayform::Error naming that part.
#pragma once

#include "rayform/math/math.h"
#include "rayform/base/work_share.h"

#include <tiny_obj_loader.h>

#include <cstddef>
#include <vector>

namespace rayform::obj {

// The faces of one tinyobjloader shape: corner f's corners are
// corners[face_start[f] .. face_start[f] + face_corners[f]); faces of other
// than three corners add nothing.
struct ObjFaces {
  const std::vector<tinyobj::index_t>& corners;
  const std::vector<size_t>& face_start;
  const std::vector<unsigned char>& face_corners;
};

// The weighted normal sums of the `vertices` (x y z per position) from the
// triangles of `faces`, one per position (zero where none adds). Every
// corner's vertex_index must name a position. With a share of several
// parts, collective (every part calls it with the same arguments).
std::vector<vec3> smooth_normal_sums(const std::vector<float>& vertices, const ObjFaces& faces,
                                     const WorkShare* share = nullptr);

}  // namespace rayform::obj
