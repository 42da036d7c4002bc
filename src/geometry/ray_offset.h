// Error-bounded hit points and robust secondary rays (pbrt-v4, section 6.8;
// Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems, ch. 6, in pbrt's conservative form).
//
// A computed hit point p is carried with `error`, a per-component bound on
// its absolute error: some point of the exact surface lies in the box
// [p - error, p + error]. Units are those of p (object or world space). The
// bounds come from counting roundings (gamma_bound(n) = n u / (1 - n u) with
// u the unit roundoff of float) and are carried through instance transforms.
// A secondary ray then starts from p pushed along the geometric normal just
// far enough that the whole box, and so the surface, lies behind it. No fixed
// epsilon: the offset follows the magnitudes involved, from a 1e-4 object at
// the origin to one 1e6 away under a 1e-4 scale. (A shape smaller than its own
// error bound, such as a 1e-4 sphere at 1e6 where floats are 0.06 apart, has
// no float point inside it: rays can leave it outwards but not enter it.)
// A point with a non-finite error cannot be offset and is returned unchanged
// (no NaN is made from inf * 0).
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/math/math.h"

#include <cmath>

namespace rayform {

// A point and a conservative bound on the absolute error of each component
// (all components >= 0; same units and space as p).
struct PointError {
  vec3 p{0.f};
  vec3 error{0.f};
};

namespace detail {
// gamma_n for rounding in double (unit roundoff 2^-53), for steps done in double.
constexpr double gamma_bound_double(int n) {
  constexpr double u = 0x1p-53;
  return (n * u) / (1 - n * u);
}
}  // namespace detail

// The point b0 p0 + b1 p1 + b2 p2 of a triangle from barycentrics (as the
// intersection returns them; b0 may be 1 - b1 - b2). Error gamma(7) sum |bi pi|
// (pbrt-v4: three products and two sums, plus the rounding of the barycentrics,
// which moves the point within the triangle's plane or by O(u |p|) off it).
inline PointError triangle_point(vec3 p0, vec3 p1, vec3 p2, float b0, float b1, float b2) {
  vec3 t0 = b0 * p0, t1 = b1 * p1, t2 = b2 * p2;
  PointError r;
  r.p = (t0 + t1) + t2;
  r.error = gamma_bound(7) * (glm::abs(t0) + glm::abs(t1) + glm::abs(t2));
  return r;
}

// Reprojects p, a point computed near the sphere |x - center| = |radius|, onto
// the sphere along the direction from the centre: p' = c + (p - c) |r| / |p - c|.
// The norm is taken in double (p - c exact or nearly so, no overflow); the
// reprojected offset q = p' - c then has error gamma(5) |q| (pbrt-v4's bound for
// the all-float form, kept as margin) and adding the centre back one rounding
// more, gamma(1) |p'|. A point exactly at the centre is left where it is.
inline PointError sphere_point(vec3 p, vec3 center, float radius) {
  const double dx = double(p.x) - center.x, dy = double(p.y) - center.y, dz = double(p.z) - center.z;
  const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double scale = double(std::abs(radius)) / dist;
  vec3 q = p - center;
  if (dist > 0.0 && std::isfinite(scale)) q = vec3(float(dx * scale), float(dy * scale), float(dz * scale));
  PointError r;
  r.p = center + q;
  r.error = gamma_bound(5) * glm::abs(q) + gamma_bound(1) * glm::abs(r.p);
  return r;
}

// Projects p onto the plane n . x = offset along n (n of any non-zero length):
// p' = p - k n with k = (n . p - offset) / (n . n), evaluated in double, where
// the products of floats are exact. With S = sum |n_i p_i| + |offset| bounding
// the terms of the residual, the error of component i is
//   gamma_double(8) (|p_i| + (2|k| + S / n.n) |n_i|)    (the double steps)
// + gamma(1) |p'_i|                                     (rounding p' to float).
// A zero or non-finite n leaves p as it is, with a bound of its own rounding.
inline PointError plane_point(vec3 p, vec3 normal, float offset) {
  const double nx = normal.x, ny = normal.y, nz = normal.z;
  const double nn = nx * nx + ny * ny + nz * nz;
  const double res = (nx * p.x + ny * p.y + nz * p.z) - double(offset);
  const double k = res / nn;
  PointError r;
  if (!(nn > 0.0) || !std::isfinite(k)) {
    r.p = p;
    r.error = gamma_bound(1) * glm::abs(p);
    return r;
  }
  r.p = vec3(float(p.x - k * nx), float(p.y - k * ny), float(p.z - k * nz));
  const double s = std::abs(nx * p.x) + std::abs(ny * p.y) + std::abs(nz * p.z) + std::abs(double(offset));
  const double w = 2.0 * std::abs(k) + s / nn;
  const double g = detail::gamma_bound_double(8);
  for (int i = 0; i < 3; ++i)
    r.error[i] =
        float(g * (std::abs(double(p[i])) + w * std::abs(double(normal[i])))) + gamma_bound(1) * std::abs(r.p[i]);
  return r;
}

// The affine transform m (column-major, last row 0 0 0 1) of a point with its
// error, as pbrt-v4's Transform::operator()(Point3fi): each output component
// is (m0 x + m1 y) + (m2 z + m3), three roundings deep (a product, two levels
// of sums), so the new error is
//   gamma(3) (|m0 x| + |m1 y| + |m2 z| + |m3|),
// plus the old error carried through |m| (with its own rounding):
//   (1 + gamma(3)) (|m0| ex + |m1| ey + |m2| ez).
// So bounds stay valid from object to world space through instance transforms.
inline PointError transform_point(const mat4& m, const PointError& pe) {
  const vec3 p = pe.p, e = pe.error;
  PointError r;
  for (int i = 0; i < 3; ++i) {
    const float a = m[0][i] * p.x, b = m[1][i] * p.y, c = m[2][i] * p.z;
    r.p[i] = (a + b) + (c + m[3][i]);
    r.error[i] = gamma_bound(3) * (std::abs(a) + std::abs(b) + std::abs(c) + std::abs(m[3][i])) +
                 (1.f + gamma_bound(3)) * (std::abs(m[0][i]) * e.x + std::abs(m[1][i]) * e.y + std::abs(m[2][i]) * e.z);
  }
  return r;
}

// Instances are intersected in object space: a ray starting at the world
// point y is mapped by to_object, the float inverse of to_world, and rounded.
// Mapped back exactly by to_world, fl(to_object y) lands within this bound of
// y (per component, world units), for every point with |y| <= y_abs:
//   |A| y_abs + |b| + |L| gamma(4) (|to_object_lin| y_abs + |to_object_t|)
// where A + b is to_world * to_object - I (the inversion error, in double,
// where the products of floats are exact), L the linear part of to_world, and
// gamma(4) the rounding of the affine transform (gamma(3), pbrt-v4) plus a
// step for the double sums. Adding it to a world-space position error keeps a
// spawned origin on its side of the surface in the space it is tested in.
inline vec3 object_roundtrip_error(const mat4& to_world, const mat4& to_object, vec3 y_abs) {
  vec3 r;
  for (int i = 0; i < 3; ++i) {
    double e = 0.0;
    double b = to_world[3][i];  // row i of to_world * to_object, translation column
    for (int j = 0; j < 3; ++j) {
      double a = i == j ? -1.0 : 0.0;  // row i of to_world * to_object - I, column j
      for (int k = 0; k < 3; ++k) a += double(to_world[k][i]) * double(to_object[j][k]);
      b += double(to_world[j][i]) * double(to_object[3][j]);
      e += std::abs(a) * y_abs[j];
    }
    e += std::abs(b);
    double rounding = 0.0;  // |L| (|to_object_lin| y_abs + |to_object_t|), row i
    for (int k = 0; k < 3; ++k) {
      double row_k = std::abs(double(to_object[3][k]));
      for (int j = 0; j < 3; ++j) row_k += std::abs(double(to_object[j][k])) * y_abs[j];
      rounding += std::abs(double(to_world[k][i])) * row_k;
    }
    e += double(gamma_bound(4)) * rounding;
    r[i] = next_float_up(float(e));
  }
  return r;
}

// The origin for a ray leaving the surface point p (error p_error) in
// direction w: p moved along the geometric normal n (any non-zero length;
// world or object space, as p) by d = dot(|n^|, p_error), the largest extent
// of the error box along n^ = n / |n|, to the side w points to (the positive
// side when w is tangent), then every component along which n points rounded
// one float further that way: the rounding of the addition cannot bring the
// point back, and a point with zero error still leaves the surface.
// A zero or non-finite n offsets along w instead; a zero w as well, or a
// non-finite error, returns p.
inline vec3 offset_ray_origin(vec3 p, vec3 p_error, vec3 n, vec3 w) {
  float nn = glm::dot(n, n);
  if (!(nn > 0.f) || !std::isfinite(nn)) {
    n = w;
    nn = glm::dot(n, n);
    if (!(nn > 0.f) || !std::isfinite(nn)) return p;
  }
  // Offset d along n^ is the vector (d / |n|) n = (dot(|n|, e) / |n|^2) n.
  const float scale = glm::dot(glm::abs(n), p_error) / nn;
  if (!std::isfinite(scale)) return p;
  if (glm::dot(w, n) < 0.f) n = -n;
  vec3 o = p + scale * n;
  // Round away from the surface by one float wherever n has a component; this
  // also moves a point whose error is exactly zero strictly off the surface.
  for (int i = 0; i < 3; ++i) {
    if (n[i] > 0.f) o[i] = next_float_up(o[i]);
    else if (n[i] < 0.f) o[i] = next_float_down(o[i]);
  }
  return o;
}

// A ray leaving the surface point (p, p_error, geometric normal n) in
// direction w, over (0, infinity); t in units of |w|.
inline Ray spawn_ray(vec3 p, vec3 p_error, vec3 n, vec3 w) {
  Ray r;
  r.origin = offset_ray_origin(p, p_error, n, w);
  r.direction = w;
  r.tmin = 0.f;
  r.tmax = infinity;
  return r;
}

// The segment from a surface point to p_to (a point light): origin offset off
// the surface towards p_to, direction p_to - origin, so that p_to is at t = 1;
// tmax is the float just below 1, so the test stops short of the light itself.
// No shadow epsilon: hits with 0 < t < tmax are occluders.
inline Ray spawn_ray_to(vec3 p_from, vec3 err_from, vec3 n_from, vec3 p_to) {
  Ray r;
  r.origin = offset_ray_origin(p_from, err_from, n_from, p_to - p_from);
  r.direction = p_to - r.origin;
  r.tmin = 0.f;
  r.tmax = next_float_down(1.f);
  return r;
}

// The segment between two surface points (visibility between surfaces): both
// ends are offset off their own surfaces towards each other, so neither
// surface lies on the segment; the far end is at t = 1 and tmax is the float
// just below 1.
inline Ray spawn_ray_to(vec3 p_from, vec3 err_from, vec3 n_from, vec3 p_to, vec3 err_to, vec3 n_to) {
  const vec3 from = offset_ray_origin(p_from, err_from, n_from, p_to - p_from);
  const vec3 to = offset_ray_origin(p_to, err_to, n_to, from - p_to);
  Ray r;
  r.origin = from;
  r.direction = to - from;
  r.tmin = 0.f;
  r.tmax = next_float_down(1.f);
  return r;
}

}  // namespace rayform
