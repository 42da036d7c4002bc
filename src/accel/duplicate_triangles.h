// Exactly repeated triangles of a mesh, merged before its BVH is built: a
// file of 10^7 copies of one triangle would otherwise make every ray that
// reaches them test them all (no split separates equal boxes).
//
// Two triangles are duplicates when everything a hit on them reads is
// bit-equal: the positions of their corners in the same order (a, b, c),
// so that the ray test gives the same t and barycentrics, and at each
// corner the normal, uvs, uvs1, tangent and colour the mesh has, and the
// face material. Then the picture does not depend on which copy a ray
// reports, and so the lowest index is kept. Not merged: the same corners in
// another order (b, c, a) or reversed, whose ray tests round differently
// and whose barycentrics are permuted, and copies whose attributes differ.
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/scene/scene.h"

#include <cstdint>
#include <vector>

namespace rayform {

// The original indices of the triangles of `mesh` that are not duplicates
// of a lower one (ascending), or an empty vector when the mesh has no
// duplicates (every triangle kept).
std::vector<uint32_t> distinct_triangles(const Mesh& mesh);

// build_mesh_accel (mesh_accel.h) of `mesh` without its duplicates: hits
// report original triangle indices (the lowest of each set of duplicates).
// Collective as build_mesh_accel is (every part finds the same duplicates).
MeshAccel build_mesh_accel_without_duplicates(const Mesh& mesh, const BvhBuildOptions& options = {},
                                              const WorkShare* share = nullptr);

}  // namespace rayform
