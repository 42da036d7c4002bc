// Axis-aligned bounding box and the slab test used by the BVH traversal.
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/math/math.h"

#include <algorithm>

namespace rayform {

struct Bounds3 {
  vec3 lo{infinity};
  vec3 hi{-infinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  vec3 extent() const { return hi - lo; }
  vec3 center() const { return 0.5f * (lo + hi); }
  float surface_area() const {
    if (empty()) return 0.f;
    vec3 e = extent();
    return 2.f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  void expand(vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void expand(const Bounds3& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
};

inline Bounds3 merge(Bounds3 a, const Bounds3& b) {
  a.expand(b);
  return a;
}

// Bounds of an affinely transformed box (the eight corners, transformed).
inline Bounds3 transform_bounds(const mat4& m, const Bounds3& b) {
  Bounds3 r;
  for (int i = 0; i < 8; ++i) {
    vec3 c((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
    r.expand(transform_point(m, c));
  }
  return r;
}

// Ray data precomputed once per ray for the slab tests.
struct RaySlabs {
  vec3 origin;
  vec3 inv_dir;
  int dir_is_neg[3];
};

inline RaySlabs make_ray_slabs(const Ray& r) {
  RaySlabs s;
  s.origin = r.origin;
  s.inv_dir = 1.f / r.direction;  // +-inf for zero components, handled by the slab test
  for (int a = 0; a < 3; ++a) s.dir_is_neg[a] = s.inv_dir[a] < 0.f;
  return s;
}

// Slab test, conservative: the far distance is scaled up by 1 + 2 gamma(3) as in
// pbrt-v4 so that rounding never culls a box the ray truly passes through.
inline bool slab_hit(const vec3& lo, const vec3& hi, const RaySlabs& s, float tmin, float tmax, float* t_enter) {
  const vec3 b[2] = {lo, hi};
  float t0 = tmin, t1 = tmax;
  constexpr float far_scale = 1.f + 2.f * gamma_bound(3);
  for (int a = 0; a < 3; ++a) {
    float tn = (b[s.dir_is_neg[a]][a] - s.origin[a]) * s.inv_dir[a];
    float tf = (b[1 - s.dir_is_neg[a]][a] - s.origin[a]) * s.inv_dir[a];
    tf *= far_scale;
    // NaN (0 * inf when the origin lies on a slab of a parallel ray) keeps the old bound.
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  *t_enter = t0;
  return t0 <= t1;
}

}  // namespace rayform
