// Tangents for tangent-space normal textures when a mesh has none from its
// file (glTF TANGENT), generated per triangle corner as MikkTSpace does.
//
// Conventions (the Scene's, scene.h): a tangent is (t, w) in object space,
// t unit and perpendicular to the corner's normal n, w = +-1, and the
// bitangent is b = w cross(n, t). t points along increasing u (dP/du) and b
// along increasing v of the Scene's uvs, in which v points up (v = 1 is the
// picture's top row). glTF's v points down (the glTF reader stores 1 - v), and
// glTF's normal texture has +X right and +Y up in the picture: +Y is the
// direction of decreasing glTF v, that is of increasing Scene v, so a texel
// (x, y, z) means the normal x t + y b + z n with t, b as generated here. The
// handedness w is -1 where the uvs are mirrored (the triangle's uv winding is
// reversed relative to its normal), as in NormalTangentMirrorTest.
//
// The prepare step uses Mesh::tangents when the file gave them and only
// calls corner_tangents for meshes without.
#pragma once

#include "rayform/math/math.h"
#include "rayform/scene/scene.h"

#include <vector>

namespace rayform {

// One tangent per triangle corner (3 per triangle, in Mesh::indices order)
// for the texture coordinates of uv_set (0: Mesh::uvs, 1: Mesh::uvs1).
// Per triangle, t = dP/du and b = dP/dv solve the triangle's edges in terms
// of its uv differences; w is the sign of dot(cross(n, t), b) with n the
// corner's normal (Mesh::normals, else the face normal of the winding).
// Corners with bit-equal position, normal and uv and the same w share one
// tangent: the sum of their triangles' t, each projected on the plane
// perpendicular to n, normalised and weighted by the corner's angle, then
// projected and normalised again (Gram-Schmidt against n). Corners with
// different handedness stay apart, so mirrored uvs keep their own tangents.
// A triangle whose uvs (or positions) are degenerate contributes nothing;
// its corners take the tangent of equal corners of the other triangles if
// there are any (w = +1 preferred), else any unit vector perpendicular to n
// with w = +1. Empty when the mesh has no uvs of that set (or not one per
// position).
std::vector<vec4> corner_tangents(const Mesh& mesh, int uv_set);

}  // namespace rayform
