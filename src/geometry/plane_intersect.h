// Ray/plane intersection for the plane n . p = d (n need not be unit length).
// t = (d - n.o) / (n.dir), with both dot products formed in double: products
// of two floats are exact in double, so the only roundings are those of the
// sums (relative 2^-53 of the sum of |terms|). In float, both are
// cancellations: n.dir is tiny at grazing angles and d - n.o is small when
// the origin is near the plane but far from the world origin, and either
// could cost all the digits of t (docs/accuracy.md: float's error at grazing
// angles). In double, t is within a few float ulps of the exact
// distance for the float inputs down to angles of about 1e-8 radians and
// heights of 1e-8 |o|. A ray parallel to the plane (n.dir = 0) misses.
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/math/math.h"

namespace rayform {

inline bool intersect_plane(const Ray& r, vec3 normal, float offset, float* t_hit) {
  const double nx = normal.x, ny = normal.y, nz = normal.z;
  const double denom = nx * r.direction.x + ny * r.direction.y + nz * r.direction.z;
  if (denom == 0.0) return false;
  const double num = double(offset) - (nx * r.origin.x + ny * r.origin.y + nz * r.origin.z);
  const float t = float(num / denom);
  if (!(t > r.tmin && t < r.tmax)) return false;  // also rejects NaN
  *t_hit = t;
  return true;
}

}  // namespace rayform
