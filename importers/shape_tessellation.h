// Shapes as triangle meshes, for formats without analytic shapes: spheres as
// UV spheres, planes as large quads around the scene.
#pragma once

#include "rayform/geometry/bounds.h"
#include "rayform/scene/scene.h"

namespace rayform {

// A UV sphere of `segments` longitudes and max(2, segments / 2) bands: two pole
// vertices and (bands - 1) rings of `segments` vertices on the sphere, unit
// outward normals (p - c) / r, no uvs; 2 segments (bands - 1) triangles, none
// degenerate, counter-clockwise seen from outside.
Mesh tessellate_sphere(const Sphere& sphere, int segments);

// The plane as a square of two triangles with half-size `half_size`, centred on
// the point of the plane nearest `around`, facing the plane's normal.
Mesh plane_quad(const Plane& plane, vec3 around, float half_size);

// Where a plane's quad goes: the bounds of everything bounded in the scene
// (shapes, camera centres, light positions), world space; empty for a scene of
// planes alone. The quad's half-size is plane_quad_scale times the radius of
// these bounds (at least 1), so that it reaches the horizon to within a pixel
// for any camera inside them.
Bounds3 scene_extent(const Scene& scene);
inline constexpr float plane_quad_scale = 1000.f;

}  // namespace rayform
