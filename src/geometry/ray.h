// A ray: origin o, direction d (not necessarily unit length) and the parametric
// interval [tmin, tmax] in units of |d|.
#pragma once

#include "rayform/math/math.h"

namespace rayform {

struct Ray {
  vec3 origin{0.f};
  vec3 direction{0.f, 0.f, 1.f};
  float tmin = 0.f;
  float tmax = infinity;

  vec3 at(float t) const { return origin + t * direction; }
};

}  // namespace rayform
