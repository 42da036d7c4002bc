// Watertight ray/triangle intersection (Woop, Benthin and Wald, JCGT 2013), in
// the form pbrt-v4 documents: vertices are translated to the ray origin,
// permuted so that the ray's largest direction component becomes z, sheared so
// the ray points along +z, and the edge functions are evaluated in double when
// they round to zero, so that a ray through a shared edge or vertex is never
// lost between two triangles. A hit is accepted only when t lies in the open
// (tmin, tmax) and is larger than its own rounding-error bound. Both hold for
// floating point computed as written: compile callers with -ffp-contract=off,
// as rayform's targets are (a fused a * b - c * d breaks the first).
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/math/math.h"

#include <algorithm>

namespace rayform {

// Barycentrics: the hit point is b0*p0 + b1*p1 + b2*p2.
struct TriangleHit {
  float t;
  float b0, b1, b2;
};

// The per-ray constants and the shear below are templates on the scalar type
// T: float wherever rayform tests a triangle, double too in
// bench/accuracy/kernel_precision.cpp (the same steps a precision up).
// WiderFloat<T> is the type the edge functions are redone in when one rounds
// to zero: double for float, long double for double.
template <class T>
struct WiderFloat;
template <>
struct WiderFloat<float> {
  using type = double;
};
template <>
struct WiderFloat<double> {
  using type = long double;
};

// Per-ray constants of the watertight test (permutation and shear), computed
// once per ray and reused for every triangle the ray visits.
template <class T>
struct BasicTriangleRay {
  glm::vec<3, T> origin;
  int kx, ky, kz;
  T sx, sy, sz;
};
using TriangleRay = BasicTriangleRay<float>;

inline TriangleRay make_triangle_ray(const Ray& r) {
  TriangleRay tr;
  tr.origin = r.origin;
  vec3 ad = glm::abs(r.direction);
  tr.kz = max_dimension(ad);
  tr.kx = tr.kz + 1 == 3 ? 0 : tr.kz + 1;
  tr.ky = tr.kx + 1 == 3 ? 0 : tr.kx + 1;
  vec3 d(r.direction[tr.kx], r.direction[tr.ky], r.direction[tr.kz]);
  tr.sx = -d.x / d.z;
  tr.sy = -d.y / d.z;
  tr.sz = 1.f / d.z;
  return tr;
}

// The triangle in the ray's space: vertices relative to the origin, axes
// permuted (kz along the ray) and x, y sheared (z not yet scaled by sz), and
// the edge functions: e0 for the edge b-c (weight of p0), e1 for c-a, e2 for
// a-b, redone in WiderFloat<T> when one rounds to zero.
template <class T>
struct BasicShearedTriangle {
  glm::vec<3, T> a, b, c;
  T e0, e1, e2;
};
using ShearedTriangle = BasicShearedTriangle<float>;

template <class T>
inline BasicShearedTriangle<T> shear_triangle(const BasicTriangleRay<T>& r, glm::vec<3, T> p0, glm::vec<3, T> p1,
                                              glm::vec<3, T> p2) {
  using V = glm::vec<3, T>;
  using W = typename WiderFloat<T>::type;
  V a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
  a = V(a[r.kx], a[r.ky], a[r.kz]);
  b = V(b[r.kx], b[r.ky], b[r.kz]);
  c = V(c[r.kx], c[r.ky], c[r.kz]);
  a.x += r.sx * a.z;
  a.y += r.sy * a.z;
  b.x += r.sx * b.z;
  b.y += r.sy * b.z;
  c.x += r.sx * c.z;
  c.y += r.sy * c.z;
  T e0 = b.x * c.y - b.y * c.x;
  T e1 = c.x * a.y - c.y * a.x;
  T e2 = a.x * b.y - a.y * b.x;
  if (e0 == T(0) || e1 == T(0) || e2 == T(0)) {
    e0 = T(W(b.x) * W(c.y) - W(b.y) * W(c.x));
    e1 = T(W(c.x) * W(a.y) - W(c.y) * W(a.x));
    e2 = T(W(a.x) * W(b.y) - W(a.y) * W(b.x));
  }
  return {a, b, c, e0, e1, e2};
}

// Returns true and fills *hit when the ray hits the triangle with tmin < t < tmax.
inline bool intersect_triangle(const TriangleRay& r, vec3 p0, vec3 p1, vec3 p2, float tmin, float tmax,
                               TriangleHit* hit) {
  auto [a, b, c, e0, e1, e2] = shear_triangle(r, p0, p1, p2);
  if ((e0 < 0.f || e1 < 0.f || e2 < 0.f) && (e0 > 0.f || e1 > 0.f || e2 > 0.f)) return false;
  float det = e0 + e1 + e2;
  if (det == 0.f) return false;  // degenerate or edge-on triangle

  // Largest |z| of the translated vertices before the scaling by sz, in scene
  // units: the sheared x + sx z and y + sy z round relative to it (|sx|, |sy| <= 1).
  const float max_z = std::max({std::abs(a.z), std::abs(b.z), std::abs(c.z)});
  a.z *= r.sz;
  b.z *= r.sz;
  c.z *= r.sz;
  float t_scaled = e0 * a.z + e1 * b.z + e2 * c.z;
  // Behind tmin on the scaled distance (avoids the division for those hits).
  // tmax is tested on t alone, so that whether a hit is reported depends only on
  // its t and not on the bound: closest-hit traversals find the same hit
  // whatever order they meet the triangles in (mesh_accel_kernel.h).
  if (det < 0.f && t_scaled >= tmin * det) return false;
  if (det > 0.f && t_scaled <= tmin * det) return false;

  float inv_det = 1.f / det;
  float t = t_scaled * inv_det;
  // The scaled test above can pass a t that the division rounds onto tmin:
  // check the interval on t itself, open at both ends.
  if (!(t > tmin && t < tmax)) return false;

  // Conservative bound on the error of t (pbrt-v4, section 6.8.7): reject hits
  // whose distance cannot be told apart from zero. This also rejects the
  // surface a ray starts on when its origin was not moved off it.
  float max_zt = std::max({std::abs(a.z), std::abs(b.z), std::abs(c.z)});
  float delta_z = gamma_bound(3) * max_zt;
  float max_xt = std::max({std::abs(a.x), std::abs(b.x), std::abs(c.x)});
  float max_yt = std::max({std::abs(a.y), std::abs(b.y), std::abs(c.y)});
  // The sheared x + sx z and y + sy z round relative to the unscaled max_z.
  // (pbrt-v4 adds the scaled max_zt here, which is in units of t: too small a
  // bound when |d| > 1, too large, rejecting true hits, when |d| < 1.)
  float delta_x = gamma_bound(5) * (max_xt + max_z);
  float delta_y = gamma_bound(5) * (max_yt + max_z);
  float delta_e = 2.f * (gamma_bound(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  float max_e = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
  float delta_t = 3.f * (gamma_bound(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * std::abs(inv_det);
  if (!(t > delta_t)) return false;

  hit->t = t;
  hit->b0 = e0 * inv_det;
  hit->b1 = e1 * inv_det;
  hit->b2 = e2 * inv_det;
  return true;
}

inline bool intersect_triangle(const Ray& r, vec3 p0, vec3 p1, vec3 p2, TriangleHit* hit) {
  return intersect_triangle(make_triangle_ray(r), p0, p1, p2, r.tmin, r.tmax, hit);
}

}  // namespace rayform
