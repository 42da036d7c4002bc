// The watertight ray/triangle test of geometry/triangle_intersect.h on one
// TrianglePacket (four triangles at a time, SIMD), for the traversal kernels
// of mesh_accel_kernel.h: the per-ray constants (TriRay), the test
// (intersect_packet) and its results (PacketHits). Private to
// mesh_accel_traverse.cpp, whose one translation unit includes it (the
// definitions have internal linkage).
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/accel/simd4.h"
#include "rayform/geometry/ray.h"
#include "rayform/geometry/triangle_intersect.h"
#include "rayform/math/math.h"

namespace rayform {
namespace {

using simd::f4;
using simd::m4;

// Per-ray constants of the watertight triangle test (make_triangle_ray), for
// four triangles at a time: the permutation as packet rows, the shear, the
// permuted origin.
struct TriRay {
  int kx, ky, kz;
  f4 okx, oky, okz, sx, sy, sz;
  float tmin;

  TriRay() = default;  // uninitialised, to be assigned
  explicit TriRay(const Ray& ray) {
    const TriangleRay tr = make_triangle_ray(ray);
    kx = tr.kx;
    ky = tr.ky;
    kz = tr.kz;
    okx = simd::splat(tr.origin[kx]);
    oky = simd::splat(tr.origin[ky]);
    okz = simd::splat(tr.origin[kz]);
    sx = simd::splat(tr.sx);
    sy = simd::splat(tr.sy);
    sz = simd::splat(tr.sz);
    tmin = ray.tmin;
  }
};

// Results of the watertight test on one packet: lanes hit with tmin < t < tmax
// in `mask`, lanes hit at exactly t == tmax in `tie_mask` (closest-hit kernels
// break such ties by packet slot, mesh_accel_kernel.h).
struct PacketHits {
  int mask = 0, tie_mask = 0;
  f4 t, e0, e1, e2, inv_det;
};

// intersect_triangle of geometry/triangle_intersect.h on four triangles: the
// same float operations in the same order, lane by lane, so the same hits and
// the same values (bvh_test checks this bit for bit against the scalar test).
// Keep the two in step. One difference: `front` below accepts a lane whose
// vertices all lie in front by more than their z error without the t bound,
// which the scalar test always applies (and which rejects hits on extreme
// slivers, e.g. 2000 x 2e-7 at distance 1, that this test keeps).
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline PacketHits
intersect_packet(const TrianglePacket& p, const TriRay& r, float tmax) {
  using namespace simd;
  PacketHits h;
  // Vertices relative to the origin, permuted (rows kx, ky, kz of each vertex), sheared.
  f4 ax = load(p.v[0 + r.kx]) - r.okx, ay = load(p.v[0 + r.ky]) - r.oky, az = load(p.v[0 + r.kz]) - r.okz;
  f4 bx = load(p.v[3 + r.kx]) - r.okx, by = load(p.v[3 + r.ky]) - r.oky, bz = load(p.v[3 + r.kz]) - r.okz;
  f4 cx = load(p.v[6 + r.kx]) - r.okx, cy = load(p.v[6 + r.ky]) - r.oky, cz = load(p.v[6 + r.kz]) - r.okz;
  ax = ax + r.sx * az;
  ay = ay + r.sy * az;
  bx = bx + r.sx * bz;
  by = by + r.sy * bz;
  cx = cx + r.sx * cz;
  cy = cy + r.sy * cz;

  f4 e0 = bx * cy - by * cx;
  f4 e1 = cx * ay - cy * ax;
  f4 e2 = ax * by - ay * bx;
  const f4 zero = splat(0.f);
  int zero_lanes = mask_bits((e0 == zero) | (e1 == zero) | (e2 == zero));
  if (zero_lanes) {
    // An edge function rounded to zero: that lane's three are redone in double.
    alignas(16) float axs[4], ays[4], bxs[4], bys[4], cxs[4], cys[4], e0s[4], e1s[4], e2s[4];
    store(axs, ax);
    store(ays, ay);
    store(bxs, bx);
    store(bys, by);
    store(cxs, cx);
    store(cys, cy);
    store(e0s, e0);
    store(e1s, e1);
    store(e2s, e2);
    for (int i = 0; i < 4; ++i) {
      if (!(zero_lanes >> i & 1)) continue;
      e0s[i] = float(double(bxs[i]) * double(cys[i]) - double(bys[i]) * double(cxs[i]));
      e1s[i] = float(double(cxs[i]) * double(ays[i]) - double(cys[i]) * double(axs[i]));
      e2s[i] = float(double(axs[i]) * double(bys[i]) - double(ays[i]) * double(bxs[i]));
    }
    e0 = load(e0s);
    e1 = load(e1s);
    e2 = load(e2s);
  }
  m4 has_neg = (e0 < zero) | (e1 < zero) | (e2 < zero);
  m4 has_pos = (e0 > zero) | (e1 > zero) | (e2 > zero);
  f4 det = e0 + e1 + e2;
  m4 valid = ~((has_neg & has_pos) | (det == zero));
  if (mask_bits(valid) == 0) return h;

  // std::max({a, b, c}) keeps the first of equal maxima, as vmax(next, current)
  // does; std::min({a, b, c}) likewise with vmin(next, current).
  const f4 max_z = vmax(vabs(cz), vmax(vabs(bz), vabs(az)));
  az = az * r.sz;
  bz = bz * r.sz;
  cz = cz * r.sz;
  f4 t_scaled = e0 * az + e1 * bz + e2 * cz;
  const f4 tmin4 = splat(r.tmin), tmax4 = splat(tmax);
  f4 tmin_det = tmin4 * det;
  m4 neg = det<zero, pos = det> zero;
  valid = andnot(valid, neg & (t_scaled >= tmin_det));
  valid = andnot(valid, pos & (t_scaled <= tmin_det));
  if (mask_bits(valid) == 0) return h;

  f4 inv_det = splat(1.f) / det;
  f4 t = t_scaled * inv_det;
  valid = valid & (t > tmin4) & (t <= tmax4);

  // In front of the origin despite rounding: every vertex in front by more
  // than its z error, or else t above the conservative bound on its error.
  f4 max_zt = vmax(vabs(cz), vmax(vabs(bz), vabs(az)));
  f4 delta_z = splat(gamma_bound(3)) * max_zt;
  m4 front = vmin(cz, vmin(bz, az)) > delta_z;
  if (mask_bits(andnot(valid, front))) {
    f4 max_xt = vmax(vabs(cx), vmax(vabs(bx), vabs(ax)));
    f4 max_yt = vmax(vabs(cy), vmax(vabs(by), vabs(ay)));
    f4 delta_x = splat(gamma_bound(5)) * (max_xt + max_z);
    f4 delta_y = splat(gamma_bound(5)) * (max_yt + max_z);
    f4 delta_e = splat(2.f) * (splat(gamma_bound(2)) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    f4 max_e = vmax(vabs(e2), vmax(vabs(e1), vabs(e0)));
    f4 delta_t =
        splat(3.f) * (splat(gamma_bound(3)) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * vabs(inv_det);
    valid = valid & (front | (t > delta_t));
  }
  h.mask = mask_bits(valid & (t < tmax4));
  h.tie_mask = mask_bits(valid & (t == tmax4));
  h.t = t;
  h.e0 = e0;
  h.e1 = e1;
  h.e2 = e2;
  h.inv_det = inv_det;
  return h;
}

}  // namespace
}  // namespace rayform
