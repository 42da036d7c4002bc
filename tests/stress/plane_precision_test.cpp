// Plane precision at grazing angles: rays meeting a plane of random
// orientation at 1e-7 .. 1e-1 radians, from 1e-3 .. 1e3 above it and up to
// 1e4 away from the origin, against a long double reference from the same
// float inputs.
//
// Stated bound: every such ray hits (the reference says so), and the hit
// distance is within gamma(4) |t*| of the exact one: the products of floats
// are exact in double, so the numerator d - n.o and the denominator n.dir
// carry relative errors of order 2^-53 (Sigma |terms|) / |value|, far below
// float rounding for these inputs; the final rounding to float adds one ulp.
// The fixed-epsilon version (float, |n.dir| < 1e-6 treated as parallel,
// t > 1e-4) is checked against the same bound.
#include "rayform/geometry/plane_intersect.h"
#include "stress_common.h"

namespace rayform::stress {
namespace {

bool naive_plane(vec3 o, vec3 d, vec3 n, float offset, float* t_hit) {
  float denom = glm::dot(n, d);
  if (std::abs(denom) < 1e-6f) return false;
  float t = (offset - glm::dot(n, o)) / denom;
  if (!(t > 1e-4f)) return false;
  *t_hit = t;
  return true;
}

struct Counts {
  int64_t samples = 0, ours_wrong = 0, ours_t = 0, naive_wrong = 0, naive_t = 0;
  double ours_max_rel = 0, naive_max_rel = 0;
  Counts& operator+=(const Counts& o) {
    samples += o.samples;
    ours_wrong += o.ours_wrong;
    ours_t += o.ours_t;
    naive_wrong += o.naive_wrong;
    naive_t += o.naive_t;
    ours_max_rel = std::max(ours_max_rel, o.ours_max_rel);
    naive_max_rel = std::max(naive_max_rel, o.naive_max_rel);
    return *this;
  }
};

TEST(StressPlane, GrazingAnglesAgainstLongDouble) {
  const int64_t n = scaled(1000000);
  Counts c = parallel_samples<Counts>(n, 10000, 31, [](Rng& rng, Counts& k, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const dvec3 nd = rng.unit_vector();
      const vec3 normal = vec3(nd * (rng.uniform() < 0.25 ? rng.log_uniform(1e-2, 1e2) : 1.0));
      const dvec3 q = rng.unit_vector() * rng.log_uniform(1e-3, 1e4);  // a point of the plane
      const float offset = float(glm::dot(dvec3(normal), q));
      // An orthonormal frame (t1, t2, n) of the plane.
      const dvec3 nu = glm::normalize(dvec3(normal));
      const dvec3 t1 = glm::normalize(glm::cross(nu, std::abs(nu.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0)));
      const dvec3 t2 = glm::cross(nu, t1);
      const double h = rng.log_uniform(1e-3, 1e3) * (rng.uniform() < 0.5 ? -1.0 : 1.0);
      const double phi = rng.uniform(0.0, 6.283185307179586);
      const vec3 o = vec3(q + h * nu + rng.uniform(0.0, 1e3) * (std::cos(phi) * t1 + std::sin(phi) * t2));
      const double theta = rng.log_uniform(1e-7, 1e-1);
      const double psi = rng.uniform(0.0, 6.283185307179586);
      dvec3 dir =
          std::cos(theta) * (std::cos(psi) * t1 + std::sin(psi) * t2) - (h > 0 ? 1.0 : -1.0) * std::sin(theta) * nu;
      if (rng.uniform() < 0.25) dir *= rng.log_uniform(1e-3, 1e3);
      const vec3 d = vec3(dir);

      // Reference from the float inputs.
      const lvec3 lo(o), ld_(d), ln(normal);
      const ld denom = dot(ln, ld_);
      const ld num = ld(offset) - dot(ln, lo);
      const ld t_ref = num / denom;
      if (!(denom != 0 && t_ref > 0)) continue;  // rounding of the inputs turned it away: not a test case
      ++k.samples;
      const ld tol = ld(gamma_bound(4)) * t_ref;

      Ray ray;
      ray.origin = o;
      ray.direction = d;
      float t = 0.f;
      if (!intersect_plane(ray, normal, offset, &t)) {
        ++k.ours_wrong;
      } else {
        const ld err = std::abs(ld(t) - t_ref);
        k.ours_t += err > tol;
        k.ours_max_rel = std::max(k.ours_max_rel, double(err / t_ref));
      }
      if (!naive_plane(o, d, normal, offset, &t)) {
        ++k.naive_wrong;
      } else {
        const ld err = std::abs(ld(t) - t_ref);
        k.naive_t += err > tol;
        k.naive_max_rel = std::max(k.naive_max_rel, double(err / t_ref));
      }
    }
  });
  std::cout << "[stress] plane: " << c.samples << " grazing rays; ours: " << c.ours_wrong << " misses, " << c.ours_t
            << " distances beyond gamma(4) |t| (largest relative error " << c.ours_max_rel
            << "); float with eps: " << c.naive_wrong << " misses, " << c.naive_t
            << " beyond the bound (largest relative error " << c.naive_max_rel << ")\n";
  report("plane", c.samples, c.ours_wrong + c.ours_t, c.naive_wrong + c.naive_t, "float_eps");
  EXPECT_EQ(c.ours_wrong, 0);
  EXPECT_EQ(c.ours_t, 0);
  EXPECT_GT(c.naive_wrong + c.naive_t, 0);
}

}  // namespace
}  // namespace rayform::stress
