// Ray/sphere intersection that keeps its precision for small spheres far away
// and for large spheres seen from near by (Haines et al., "Precision
// Improvements for Ray/Sphere Intersection", Ray Tracing Gems, ch. 7):
// the discriminant is formed from the distance of the centre to the ray line
// rather than as b^2 - 4ac, and the two roots come from the numerically stable
// q-form. The direction need not be unit length; t is in units of |d|.
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/math/math.h"

namespace rayform {

// Both roots t0 <= t1 of |o + t d - c| = r, or false when the ray's line misses.
inline bool sphere_roots(vec3 origin, vec3 direction, vec3 center, float radius, float* t0, float* t1) {
  vec3 f = origin - center;
  float a = glm::dot(direction, direction);
  if (!(a > 0.f)) return false;
  float b_half = -glm::dot(f, direction);  // -(b/2) of a t^2 + b t + c
  float c = glm::dot(f, f) - radius * radius;
  // Closest point of the line to the centre, l = f + (b_half/a) d; then
  // b_half^2 - a c = a (r^2 - |l|^2), free of the catastrophic cancellation.
  vec3 l = f + (b_half / a) * direction;
  float disc = a * (radius - glm::length(l)) * (radius + glm::length(l));
  if (disc < 0.f) return false;
  float q = b_half + std::copysign(std::sqrt(disc), b_half);
  float r0 = q == 0.f ? 0.f : c / q;
  float r1 = q / a;
  *t0 = std::min(r0, r1);
  *t1 = std::max(r0, r1);
  return true;
}

// Nearest root inside (tmin, tmax); a ray starting inside sees the far side.
inline bool intersect_sphere(const Ray& r, vec3 center, float radius, float* t_hit) {
  float t0, t1;
  if (!sphere_roots(r.origin, r.direction, center, radius, &t0, &t1)) return false;
  if (t0 > r.tmin && t0 < r.tmax) {
    *t_hit = t0;
    return true;
  }
  if (t1 > r.tmin && t1 < r.tmax) {
    *t_hit = t1;
    return true;
  }
  return false;
}

}  // namespace rayform
