// Deterministic procedural meshes, made by our own code: closed test shapes
// for the stress suite and meshes of any size for the benchmarks.
#pragma once

#include "rayform/scene/scene.h"

#include <cstdint>

namespace rayform {

// Unit icosahedron subdivided `levels` times and projected onto the unit
// sphere: 20 * 4^levels triangles, closed, shared vertices, outward normals.
Mesh make_icosphere(int levels);

// Axis-aligned cube [-1, 1]^3: 12 triangles, 8 shared vertices, closed.
Mesh make_cube();

// A closed, bumpy torus of about `target_triangles` triangles (the exact
// count is 2 * rings * segments). Radii 1 and 0.35 with a deterministic
// displacement from `seed`, so that the BVH sees uneven detail. Positions and
// smooth normals; no uvs.
Mesh make_bumpy_torus(size_t target_triangles, uint32_t seed = 1);

// A grid of `nx` x `ny` quads on [0,1]^2 in the z = 0 plane with uvs.
Mesh make_grid(int nx, int ny);

}  // namespace rayform
