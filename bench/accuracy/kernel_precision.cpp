// Float against double intersection kernels: run time and error.
//
// The three kernels of src/geometry (watertight triangle, Ray Tracing Gems
// sphere, plane with double dot products) as templates on the scalar type T:
// the triangle test's shear and edge functions are the production header's
// own template (shear_triangle); its ray constants (make_tri_ray, as
// make_triangle_ray), the rest of that test and the sphere and plane kernels
// are copied here, line for line. The float instantiation is checked bit for
// bit against the production headers on every ray below (any difference is
// reported and makes the program fail), so the double instantiation is the
// same algorithm with every float step done in double. (The production
// headers' tests take float only: the SIMD mesh kernel mirrors the float
// triangle test bit-exactly and the renderer has no use for a double path.)
//
// Both instantiations get the same float inputs (rays, triangles, spheres,
// planes rounded to float once) and are compared with a long double reference
// computed from those same inputs, so the error is the kernel's own.
// Per kernel and ray set: ns per test (best of 5 passes), wrong hit/miss
// against the reference, and the relative error |t - t*| / t* of t over the
// hits both agree on (max and RMS; for spheres the error is taken relative to
// |o - c| + r instead of t, see measure()). Output: a markdown table on stdout.
//   build: c++ -std=c++20 -O3 -DNDEBUG -ffp-contract=off -I build/include
//          bench/accuracy/kernel_precision.cpp -o kernel_precision
//          (cmake's configure makes build/include/rayform)
//   usage: kernel_precision [rays per set, default 200000]
#include "rayform/geometry/plane_intersect.h"
#include "rayform/geometry/sphere_intersect.h"
#include "rayform/geometry/triangle_intersect.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace rayform;
using ld = long double;

namespace tk {  // the kernels on T

template <class T>
using v3 = glm::vec<3, T, glm::defaultp>;
template <class T>
constexpr T gamma_t(int n) {
  constexpr T u = std::numeric_limits<T>::epsilon() * T(0.5);
  return (T(n) * u) / (T(1) - T(n) * u);
}
template <class T>
int max_dim(v3<T> v) {
  return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}

template <class T>
BasicTriangleRay<T> make_tri_ray(v3<T> o, v3<T> dir) {
  BasicTriangleRay<T> tr;
  tr.origin = o;
  v3<T> ad = glm::abs(dir);
  tr.kz = max_dim(ad);
  tr.kx = tr.kz + 1 == 3 ? 0 : tr.kz + 1;
  tr.ky = tr.kx + 1 == 3 ? 0 : tr.kx + 1;
  v3<T> d(dir[tr.kx], dir[tr.ky], dir[tr.kz]);
  tr.sx = -d.x / d.z;
  tr.sy = -d.y / d.z;
  tr.sz = T(1) / d.z;
  return tr;
}
// The watertight test of triangle_intersect.h after its shear (shear_triangle,
// the production code's own, on T).
template <class T>
bool triangle(const BasicTriangleRay<T>& r, v3<T> p0, v3<T> p1, v3<T> p2, T tmin, T tmax, T* t_out) {
  auto [a, b, c, e0, e1, e2] = shear_triangle(r, p0, p1, p2);
  if ((e0 < T(0) || e1 < T(0) || e2 < T(0)) && (e0 > T(0) || e1 > T(0) || e2 > T(0))) return false;
  T det = e0 + e1 + e2;
  if (det == T(0)) return false;
  const T max_z = std::max({std::abs(a.z), std::abs(b.z), std::abs(c.z)});
  a.z *= r.sz;
  b.z *= r.sz;
  c.z *= r.sz;
  T t_scaled = e0 * a.z + e1 * b.z + e2 * c.z;
  if (det < T(0) && t_scaled >= tmin * det) return false;
  if (det > T(0) && t_scaled <= tmin * det) return false;
  T inv_det = T(1) / det;
  T t = t_scaled * inv_det;
  if (!(t > tmin && t < tmax)) return false;
  T max_zt = std::max({std::abs(a.z), std::abs(b.z), std::abs(c.z)});
  T delta_z = gamma_t<T>(3) * max_zt;
  T max_xt = std::max({std::abs(a.x), std::abs(b.x), std::abs(c.x)});
  T max_yt = std::max({std::abs(a.y), std::abs(b.y), std::abs(c.y)});
  T delta_x = gamma_t<T>(5) * (max_xt + max_z);
  T delta_y = gamma_t<T>(5) * (max_yt + max_z);
  T delta_e = T(2) * (gamma_t<T>(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  T max_e = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
  T delta_t = T(3) * (gamma_t<T>(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * std::abs(inv_det);
  if (!(t > delta_t)) return false;
  *t_out = t;
  return true;
}

template <class T>
bool sphere(v3<T> origin, v3<T> direction, v3<T> center, T radius, T tmin, T tmax, T* t_hit) {
  v3<T> f = origin - center;
  T a = glm::dot(direction, direction);
  if (!(a > T(0))) return false;
  T b_half = -glm::dot(f, direction);
  T c = glm::dot(f, f) - radius * radius;
  v3<T> l = f + (b_half / a) * direction;
  T disc = a * (radius - glm::length(l)) * (radius + glm::length(l));
  if (disc < T(0)) return false;
  T q = b_half + std::copysign(std::sqrt(disc), b_half);
  T r0 = q == T(0) ? T(0) : c / q;
  T r1 = q / a;
  T t0 = std::min(r0, r1), t1 = std::max(r0, r1);
  if (t0 > tmin && t0 < tmax) {
    *t_hit = t0;
    return true;
  }
  if (t1 > tmin && t1 < tmax) {
    *t_hit = t1;
    return true;
  }
  return false;
}

// Production: inputs float, dot products in double, t rounded to float.
// The double variant: inputs and every step in double (no wider type).
template <class T>
bool plane(v3<T> o, v3<T> dir, v3<T> normal, T offset, T tmin, T tmax, T* t_hit) {
  const double nx = normal.x, ny = normal.y, nz = normal.z;
  const double denom = nx * dir.x + ny * dir.y + nz * dir.z;
  if (denom == 0.0) return false;
  const double num = double(offset) - (nx * o.x + ny * o.y + nz * o.z);
  const T t = T(num / denom);
  if (!(t > tmin && t < tmax)) return false;
  *t_hit = t;
  return true;
}

}  // namespace tk

// ---- inputs -----------------------------------------------------------------

struct Rng {  // SplitMix64, as the stress suite
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double u() { return double(next() >> 11) * 0x1p-53; }
  double u(double a, double b) { return a + (b - a) * u(); }
  double log_u(double lo, double hi) { return lo * std::pow(hi / lo, u()); }
  dvec3 unit() {
    double z = u(-1, 1), phi = u(0, 6.283185307179586);
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
};
dvec3 perpendicular(dvec3 n, Rng& g) { return glm::normalize(glm::cross(n, g.unit())); }

// One test: a float ray and a float primitive (p[0..2] triangle vertices;
// sphere: p[0] centre, s radius; plane: p[0] normal, s offset).
struct Case {
  vec3 o, d;
  vec3 p[3];
  float s = 0.f;
};

struct RefHit {
  bool hit = false;
  ld t = 0;
};

struct lv {
  ld x, y, z;
};
lv L(vec3 v) { return {v.x, v.y, v.z}; }
lv operator-(lv a, lv b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
lv operator+(lv a, lv b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
lv operator*(ld s, lv a) { return {s * a.x, s * a.y, s * a.z}; }
ld dot(lv a, lv b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
lv cross(lv a, lv b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// Exact-ish references in long double (64-bit significand: products of floats exact).
RefHit ref_triangle(const Case& c) {
  lv o = L(c.o), d = L(c.d), a = L(c.p[0]) - o, b = L(c.p[1]) - o, e = L(c.p[2]) - o;
  // Signed volumes: the line o + t d crosses the triangle iff the three have one sign.
  ld w0 = dot(d, cross(b, e)), w1 = dot(d, cross(e, a)), w2 = dot(d, cross(a, b));
  if ((w0 < 0 || w1 < 0 || w2 < 0) && (w0 > 0 || w1 > 0 || w2 > 0)) return {};
  ld det = w0 + w1 + w2;
  if (det == 0) return {};
  lv n = cross(L(c.p[1]) - L(c.p[0]), L(c.p[2]) - L(c.p[0]));
  ld t = dot(n, a) / dot(n, d);
  if (!(t > 0)) return {};
  return {true, t};
}
RefHit ref_sphere(const Case& c) {
  lv f = L(c.o) - L(c.p[0]), d = L(c.d);
  ld r = std::abs(ld(c.s)), a = dot(d, d), b = dot(f, d);
  lv l = f - (b / a) * d;
  ld ll = std::sqrt(dot(l, l));
  ld disc = (r - ll) * (r + ll);
  if (disc < 0) return {};
  ld q = -b - std::copysign(std::sqrt(a * disc), b);
  ld cc = dot(f, f) - r * r;
  ld t0 = q == 0 ? 0 : cc / q, t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > 0) return {true, t0};
  if (t1 > 0) return {true, t1};
  return {};
}
RefHit ref_plane(const Case& c) {
  lv n = L(c.p[0]);
  ld den = dot(n, L(c.d));
  if (den == 0) return {};
  ld t = (ld(c.s) - dot(n, L(c.o))) / den;
  if (!(t > 0)) return {};
  return {true, t};
}

vec3 F(dvec3 v) { return vec3(v); }

// Triangle sets. Interior: triangles of size 1e-2 .. 1e2 near the origin, rays
// from 2 .. 50 sizes away aimed at interior points. Hard: triangles translated
// 1e2 .. 1e5 and rays aimed within 1e-7 .. 1e-3 (relative) of an edge, either
// side, from grazing to head-on.
std::vector<Case> triangle_cases(int n, bool hard, uint64_t seed) {
  Rng g(seed);
  std::vector<Case> v(n);
  for (Case& c : v) {
    double size = g.log_u(1e-2, 1e2);
    dvec3 centre = hard ? g.log_u(1e2, 1e5) * g.unit() : size * g.u(0, 2) * g.unit();
    dvec3 q[3];
    for (auto& x : q) x = centre + size * g.unit();
    for (int k = 0; k < 3; ++k) c.p[k] = F(q[k]);
    dvec3 p0(c.p[0]), p1(c.p[1]), p2(c.p[2]);
    dvec3 aim;
    if (!hard) {
      double b1 = g.u(0.02, 0.96), b2 = g.u(0.02, 0.98 - b1);
      aim = (1 - b1 - b2) * p0 + b1 * p1 + b2 * p2;
    } else {
      double u = g.u(0.05, 0.95);
      dvec3 e0 = p1 - p0, onedge = p0 + u * e0;
      dvec3 inward = (p2 - p0) - glm::dot(p2 - p0, e0) / glm::dot(e0, e0) * e0;  // towards p2, in-plane
      aim = onedge + (g.u() < 0.5 ? -1.0 : 1.0) * g.log_u(1e-7, 1e-3) * inward;
    }
    dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    double cosang = hard ? g.log_u(1e-2, 1.0) : g.u(0.2, 1.0);
    dvec3 dir = cosang * n + std::sqrt(1 - cosang * cosang) * perpendicular(n, g);
    if (g.u() < 0.5) dir = -dir;
    double dist = size * g.log_u(2, 50);
    c.o = F(aim - dist * dir);
    c.d = F(dir * g.log_u(0.1, 10.0));
  }
  return v;
}

// Sphere sets. Random: radius 1e-2 .. 1e2 near the origin, seen from 2 .. 100
// radii, aimed within the disc. Hard (the stress suite's ranges): radius
// 1e-4 .. 1e6, centre up to 1e6 from the origin, seen from 1e-4 .. 1e7 beyond
// the surface (an eighth from inside), aimed at random points near the disc.
std::vector<Case> sphere_cases(int n, bool hard, uint64_t seed) {
  Rng g(seed);
  std::vector<Case> v(n);
  for (Case& c : v) {
    double r = hard ? g.log_u(1e-4, 1e6) : g.log_u(1e-2, 1e2);
    dvec3 centre = hard ? g.log_u(1e-3, 1e6) * g.unit() : r * g.u(0, 1) * g.unit();
    dvec3 w = g.unit();
    dvec3 o = (hard && g.u() < 0.125) ? centre + r * g.u(0, 0.99) * w
                                      : centre + (hard ? r + g.log_u(1e-4, 1e7) : r * g.log_u(2, 100)) * w;
    dvec3 target = centre + r * g.u(0, hard ? 1.2 : 0.999) * perpendicular(-w, g);
    dvec3 dir = glm::normalize(target - o) * (g.u() < 0.25 ? g.log_u(1e-2, 1e2) : 1.0);
    c.o = F(o);
    c.d = F(dir);
    c.p[0] = F(centre);
    c.s = float(r);
  }
  return v;
}

// Plane sets. Random: unit normals, origin 1 .. 100 above, angles 0.1 .. 1.5
// rad. Hard (grazing, as the stress suite): normals of length 0.01 .. 100 for
// a quarter, angles 1e-7 .. 1e-1 rad, height 1e-3 .. 1e3, origins up to 1e4
// from the world origin.
std::vector<Case> plane_cases(int n, bool hard, uint64_t seed) {
  Rng g(seed);
  std::vector<Case> v(n);
  for (Case& c : v) {
    dvec3 nu = g.unit();
    double len = hard && g.u() < 0.25 ? g.log_u(1e-2, 1e2) : 1.0;
    dvec3 base = (hard ? g.log_u(1e-2, 1e4) : g.u(0, 10)) * g.unit();
    double h = hard ? g.log_u(1e-3, 1e3) : g.u(1, 100);
    double ang = hard ? g.log_u(1e-7, 1e-1) : g.u(0.1, 1.5);
    dvec3 o = base + h * nu;
    dvec3 dir = -std::sin(ang) * nu + std::cos(ang) * perpendicular(nu, g);
    c.p[0] = F(len * nu);
    c.s = float(glm::dot(dvec3(c.p[0]), base));
    c.o = F(o);
    c.d = F(dir);
  }
  return v;
}

// ---- measurement --------------------------------------------------------------

enum class Kind { triangle, sphere, plane };

template <class T>
bool run(Kind k, const Case& c, T* t) {
  using V = tk::v3<T>;
  const V o(c.o), d(c.d);
  const T tmax = std::numeric_limits<T>::infinity();
  switch (k) {
    case Kind::triangle:
      return tk::triangle<T>(tk::make_tri_ray<T>(o, d), V(c.p[0]), V(c.p[1]), V(c.p[2]), T(0), tmax, t);
    case Kind::sphere: return tk::sphere<T>(o, d, V(c.p[0]), T(c.s), T(0), tmax, t);
    case Kind::plane: return tk::plane<T>(o, d, V(c.p[0]), T(c.s), T(0), tmax, t);
  }
  return false;
}

bool production(Kind k, const Case& c, float* t) {
  Ray r;
  r.origin = c.o;
  r.direction = c.d;
  switch (k) {
    case Kind::triangle: {
      TriangleHit h;
      if (!intersect_triangle(r, c.p[0], c.p[1], c.p[2], &h)) return false;
      *t = h.t;
      return true;
    }
    case Kind::sphere: return intersect_sphere(r, c.p[0], c.s, t);
    case Kind::plane: return intersect_plane(r, c.p[0], c.s, t);
  }
  return false;
}

struct Stats {
  double ns = 0;
  int64_t wrong = 0, both = 0;
  double max_rel = 0, sum_sq = 0;
};

template <class T>
Stats measure(Kind k, const std::vector<Case>& cases, const std::vector<RefHit>& ref) {
  Stats s;
  double best = 1e300;
  volatile double sink = 0;
  for (int pass = 0; pass < 5; ++pass) {
    auto t0 = std::chrono::steady_clock::now();
    double acc = 0;
    for (const Case& c : cases) {
      T t;
      if (run<T>(k, c, &t)) acc += double(t);
    }
    auto t1 = std::chrono::steady_clock::now();
    sink = sink + acc;
    best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count());
  }
  s.ns = best / double(cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    T t;
    bool hit = run<T>(k, cases[i], &t);
    if (hit != ref[i].hit) {
      ++s.wrong;
      continue;
    }
    if (!hit) continue;
    ++s.both;
    // Triangles and planes: |t - t*| / t*. Spheres: |t - t*| |d| / (|o - c| + r),
    // the error in units of the scale the inputs are given to (a ray starting
    // within a float spacing of a 1e6 sphere has t* near 0, and no kernel can
    // get that t to a relative precision).
    const Case& c = cases[i];
    double scale = double(ref[i].t);
    if (k == Kind::sphere) {
      lv f = L(c.o) - L(c.p[0]), d = L(c.d);
      scale = double((std::sqrt(dot(f, f)) + std::abs(ld(c.s))) / std::sqrt(dot(d, d)));
    }
    double rel = double(std::abs(ld(t) - ref[i].t)) / scale;
    s.max_rel = std::max(s.max_rel, rel);
    s.sum_sq += rel * rel;
  }
  return s;
}

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200000;
  struct Set {
    const char* name;
    Kind kind;
    bool hard;
  } sets[] = {{"triangle, interior", Kind::triangle, false},
              {"triangle, 1e-7..1e-3 from an edge, at 1e2..1e5", Kind::triangle, true},
              {"sphere, random", Kind::sphere, false},
              {"sphere, radius 1e-4..1e6 at up to 1e6, from 1e-4..1e7", Kind::sphere, true},
              {"plane, random", Kind::plane, false},
              {"plane, grazing 1e-7..1e-1 rad", Kind::plane, true}};
  int bad_mirror = 0;
  std::printf(
      "| kernel, ray set | rays | float ns/test | double ns/test | double/float time | "
      "float wrong hit/miss | double wrong hit/miss | float max rel. error | float RMS | "
      "double max rel. error | double RMS |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  uint64_t seed = 1;
  for (const Set& set : sets) {
    std::vector<Case> cases = set.kind == Kind::triangle ? triangle_cases(n, set.hard, seed)
                              : set.kind == Kind::sphere ? sphere_cases(n, set.hard, seed)
                                                         : plane_cases(n, set.hard, seed);
    ++seed;
    std::vector<RefHit> ref(cases.size());
    for (size_t i = 0; i < cases.size(); ++i) {
      const Case& c = cases[i];
      ref[i] = set.kind == Kind::triangle ? ref_triangle(c) : set.kind == Kind::sphere ? ref_sphere(c) : ref_plane(c);
      // The float template must be the production kernel, bit for bit.
      float a = 0.f, b = 0.f;
      bool ha = run<float>(set.kind, c, &a), hb = production(set.kind, c, &b);
      if (ha != hb || (ha && std::memcmp(&a, &b, sizeof a) != 0)) ++bad_mirror;
    }
    Stats f = measure<float>(set.kind, cases, ref);
    Stats d = measure<double>(set.kind, cases, ref);
    auto rms = [](const Stats& s) { return s.both ? std::sqrt(s.sum_sq / double(s.both)) : 0.0; };
    std::printf("| %s | %d | %.2f | %.2f | %.2f | %lld | %lld | %.2e | %.2e | %.2e | %.2e |\n", set.name, n, f.ns, d.ns,
                d.ns / f.ns, (long long)f.wrong, (long long)d.wrong, f.max_rel, rms(f), d.max_rel, rms(d));
  }
  std::printf("\nFloat template against the production headers: %d of %d tests differ (must be 0).\n", bad_mirror,
              6 * n);
  return bad_mirror == 0 ? 0 : 1;
}
