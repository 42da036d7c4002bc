// Ray/plane intersection for the plane n . p = d (n need not be unit length).
// t = (d - n.o) / (n.dir): one subtraction, one division; at grazing angles the
// denominator is small but exact to rounding, so the result stays within a few
// ulps of the true distance; a ray parallel to the plane misses.
#pragma once

#include "geometry/ray.h"
#include "math/math.h"

namespace rayform {

inline bool intersect_plane(const Ray& r, vec3 normal, float offset, float* t_hit) {
  float denom = glm::dot(normal, r.direction);
  if (denom == 0.f) return false;
  float t = (offset - glm::dot(normal, r.origin)) / denom;
  if (!(t > r.tmin && t < r.tmax)) return false;  // also rejects NaN
  *t_hit = t;
  return true;
}

}  // namespace rayform
