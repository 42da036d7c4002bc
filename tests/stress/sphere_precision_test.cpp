// Sphere precision: radii 1e-4 .. 1e6, centres up to 1e6 from the origin,
// seen from 1e-4 .. 1e7 away (also from inside), directions of any length,
// against a long double reference computed from the same float inputs.
//
// Stated bound. With f = o - c, u the unit roundoff of float and
// eta = gamma(16) (|f| + r), the float computation resolves the distance of
// the centre to the ray's line to within eta. So:
//  - hit/miss must agree with the reference unless the line passes within
//    eta of tangency (| |l| - r | <= eta, counted as ambiguous);
//  - the hit distance, in units of length (t |d|), must be within
//    gamma(16) (|f| + r) + | sqrt(r^2 - |l|^2) - sqrt(r^2 - (|l| + eta)^2) |,
//    the second term being the root's sensitivity to eta near tangency.
// The textbook b^2 - 4ac form in float with a t > 1e-4 guard is checked
// against the same bound.
#include "rayform/geometry/sphere_intersect.h"
#include "stress_common.h"

#include <algorithm>

namespace rayform::stress {
namespace {

constexpr int kGamma = 16;

// Textbook quadratic with a fixed epsilon (test only).
bool naive_sphere(vec3 o, vec3 d, vec3 c, float r, float* t_hit) {
  vec3 f = o - c;
  float a = glm::dot(d, d), b = 2.f * glm::dot(f, d), cc = glm::dot(f, f) - r * r;
  float disc = b * b - 4.f * a * cc;
  if (disc < 0.f) return false;
  float s = std::sqrt(disc);
  float t = (-b - s) / (2.f * a);
  if (t > 1e-4f) {
    *t_hit = t;
    return true;
  }
  t = (-b + s) / (2.f * a);
  if (t > 1e-4f) {
    *t_hit = t;
    return true;
  }
  return false;
}

struct Reference {
  bool hit = false;
  ld t = 0;          // nearest root > 0
  ld line_dist = 0;  // |l|, distance of the centre to the line
  ld f_len = 0;      // |o - c|
  ld d_len = 0;
};

Reference reference(vec3 of, vec3 df, vec3 cf, float rf) {
  const lvec3 o(of), d(df), c(cf);
  const ld r = std::abs(ld(rf));
  Reference ref;
  const lvec3 f = o - c;
  const ld a = dot(d, d), b = dot(f, d);
  const lvec3 l = f - (b / a) * d;
  ref.line_dist = length(l);
  ref.f_len = length(f);
  ref.d_len = std::sqrt(a);
  const ld disc = (r - ref.line_dist) * (r + ref.line_dist);
  if (disc < 0) return ref;
  const ld q = -b - std::copysign(std::sqrt(a * disc), b);
  const ld cc = dot(f, f) - r * r;
  ld t0 = q == 0 ? 0 : cc / q, t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > 0) {
    ref.hit = true;
    ref.t = t0;
  } else if (t1 > 0) {
    ref.hit = true;
    ref.t = t1;
  }
  return ref;
}

struct Counts {
  int64_t samples = 0, ref_hits = 0, ambiguous = 0;
  int64_t ours_wrong = 0, ours_t = 0, naive_wrong = 0, naive_t = 0;
  double ours_max_t_ratio = 0;  // max t error / stated bound over hits
  Counts& operator+=(const Counts& o) {
    samples += o.samples;
    ref_hits += o.ref_hits;
    ambiguous += o.ambiguous;
    ours_wrong += o.ours_wrong;
    ours_t += o.ours_t;
    naive_wrong += o.naive_wrong;
    naive_t += o.naive_t;
    ours_max_t_ratio = std::max(ours_max_t_ratio, o.ours_max_t_ratio);
    return *this;
  }
};

TEST(StressSphere, PrecisionAgainstLongDouble) {
  const int64_t n = scaled(1000000);
  Counts c = parallel_samples<Counts>(n, 10000, 21, [](Rng& rng, Counts& k, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const float r = float(rng.log_uniform(1e-4, 1e6));
      const vec3 centre = vec3(rng.unit_vector() * (rng.uniform() < 0.2 ? 0.0 : rng.log_uniform(1.0, 1e6)));
      double dist;
      do dist = rng.log_uniform(1e-4, 1e7);
      while (std::abs(dist - r) < 1e-3 * std::max(dist, double(r)));  // origins on the surface: ray_offset's job
      const vec3 o = vec3(dvec3(centre) + rng.unit_vector() * dist);
      // Aim within 1.3 r of the centre (about as many misses as hits), or anywhere from inside.
      const dvec3 target = dvec3(centre) + rng.unit_vector() * double(r) * rng.uniform(0.0, 1.3);
      dvec3 dir = glm::normalize(target - dvec3(o));
      if (rng.uniform() < 0.25) dir *= rng.log_uniform(1e-3, 1e3);  // t is in units of |d|
      const vec3 d = vec3(dir);
      if (!(glm::dot(d, d) > 0.f)) continue;
      ++k.samples;

      const Reference ref = reference(o, d, centre, r);
      k.ref_hits += ref.hit;
      const ld eta = ld(gamma_bound(kGamma)) * (ref.f_len + ld(r));
      const bool ambiguous = std::abs(ref.line_dist - ld(r)) <= eta;
      k.ambiguous += ambiguous;
      const ld rr = ld(r) * ld(r);
      const ld sens = std::abs(std::sqrt(std::max<ld>(0, rr - ref.line_dist * ref.line_dist)) -
                               std::sqrt(std::max<ld>(0, rr - (ref.line_dist + eta) * (ref.line_dist + eta))));
      const ld tol = eta + sens;  // in units of length

      auto judge = [&](bool hit, float t, int64_t& wrong, int64_t& t_err, double* max_ratio) {
        if (hit != ref.hit) {
          if (!ambiguous) ++wrong;
          return;
        }
        if (!hit) return;
        const ld err = std::abs(ld(t) - ref.t) * ref.d_len;
        if (err > tol) ++t_err;
        if (max_ratio) *max_ratio = std::max(*max_ratio, double(err / tol));
      };
      Ray ray;
      ray.origin = o;
      ray.direction = d;
      float t = 0.f;
      bool hit = intersect_sphere(ray, centre, r, &t);
      judge(hit, t, k.ours_wrong, k.ours_t, &k.ours_max_t_ratio);
      hit = naive_sphere(o, d, centre, r, &t);
      judge(hit, t, k.naive_wrong, k.naive_t, nullptr);
    }
  });
  std::cout << "[stress] sphere: " << c.samples << " rays (" << c.ref_hits << " hits in the reference, " << c.ambiguous
            << " within the tangency band); ours: " << c.ours_wrong << " wrong hit/miss, " << c.ours_t
            << " distances beyond the bound (largest error / bound " << c.ours_max_t_ratio
            << "); b^2-4ac eps=1e-4: " << c.naive_wrong << " wrong hit/miss, " << c.naive_t
            << " distances beyond the bound\n";
  report("sphere", c.samples, c.ours_wrong + c.ours_t, c.naive_wrong + c.naive_t, "textbook_quadratic_eps");
  EXPECT_EQ(c.ours_wrong, 0);
  EXPECT_EQ(c.ours_t, 0);
  EXPECT_GT(c.naive_wrong + c.naive_t, 0);
}

}  // namespace
}  // namespace rayform::stress
