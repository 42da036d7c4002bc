// The internals of the MeshAccel builder (mesh_accel.h), shared by the whole
// build (mesh_accel_build.cpp) and the build shared among the parts of a
// WorkShare (mesh_accel_share.cpp): triangle boxes (mesh_build_refs.h), then
// a binned SAH build (mesh_build_split.h) of an 8-wide tree run in parallel
// with oneTBB (mesh_build_tree.h), then the tree written depth first into
// WideBvhNodes and TrianglePackets (mesh_build_flatten.h). Deterministic: the
// same input gives the same structure whatever the number of threads
// (parallel tasks work on disjoint ranges, reductions merge in a fixed order,
// and the flattening offsets come from subtree totals). Private to those two
// files, as are the headers it includes (not installed: they include oneTBB).
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/accel/mesh_build_flatten.h"
#include "rayform/accel/mesh_build_refs.h"
#include "rayform/accel/mesh_build_split.h"
#include "rayform/accel/mesh_build_tree.h"

#include <cstdint>
#include <span>

namespace rayform::mesh_build {

// The build shared among the parts of `share` (mesh_accel_share.cpp).
MeshAccel build_shared(std::span<const vec3> positions, std::span<const uint32_t> indices,
                       const BvhBuildOptions& options, const WorkShare& share);

}  // namespace rayform::mesh_build
