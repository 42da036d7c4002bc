// Rays for tests: one from its origin, direction and (tmin, tmax).
#pragma once

#include "rayform/geometry/ray.h"

namespace rayform::test {

inline Ray make_ray(vec3 o, vec3 d, float tmin = 0.f, float tmax = infinity) {
  Ray r;
  r.origin = o;
  r.direction = d;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

}  // namespace rayform::test
