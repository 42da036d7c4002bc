// Ray/sphere intersection (src/geometry/sphere_intersect.h): hits, misses,
// rays starting inside, the open interval (tmin, tmax), non-unit directions,
// and the precision of the roots against a double-precision reference.
#include "rayform/geometry/sphere_intersect.h"
#include "test_rays.h"

#include <gtest/gtest.h>

#include <random>

namespace rayform {
namespace {

using test::make_ray;

TEST(SphereIntersect, HeadOnHitGivesNearSurface) {
  float t = -1.f;
  ASSERT_TRUE(intersect_sphere(make_ray({0, 0, 5}, {0, 0, -1}), vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 4.f);  // every quantity is a small integer: exact
  float t0 = 0.f, t1 = 0.f;
  ASSERT_TRUE(sphere_roots(vec3(0, 0, 5), vec3(0, 0, -1), vec3(0.f), 1.f, &t0, &t1));
  EXPECT_EQ(t0, 4.f);
  EXPECT_EQ(t1, 6.f);
}

TEST(SphereIntersect, OffCentreHitAndCentreNotAtOrigin) {
  // Sphere centre (1, 2, 3), radius 5; ray along +x through y = 2 + 3, z = 3:
  // tangent at x = 1. Through y = 2 + 4 (= 6): x = 1 +- 3.
  float t = 0.f;
  ASSERT_TRUE(intersect_sphere(make_ray({-10, 6, 3}, {1, 0, 0}), vec3(1, 2, 3), 5.f, &t));
  EXPECT_EQ(t, 8.f);  // x = -2: 11 - 3
}

TEST(SphereIntersect, DistanceIsInUnitsOfTheDirection) {
  float t = 0.f;
  ASSERT_TRUE(intersect_sphere(make_ray({0, 0, 5}, {0, 0, -2}), vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 2.f);
  ASSERT_TRUE(intersect_sphere(make_ray({0, 0, 5}, {0, 0, -0.5f}), vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 8.f);
}

TEST(SphereIntersect, Misses) {
  float t = 123.f;
  // Passes beside the sphere.
  EXPECT_FALSE(intersect_sphere(make_ray({1.5f, 0, 5}, {0, 0, -1}), vec3(0.f), 1.f, &t));
  // Points away from it.
  EXPECT_FALSE(intersect_sphere(make_ray({0, 0, 5}, {0, 0, 1}), vec3(0.f), 1.f, &t));
  // Sphere entirely behind the origin.
  EXPECT_FALSE(intersect_sphere(make_ray({0, 0, -5}, {0, 0, -1}), vec3(0.f), 1.f, &t));
  // Zero direction.
  EXPECT_FALSE(intersect_sphere(make_ray({0, 0, 5}, {0, 0, 0}), vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 123.f) << "a miss must not write the hit distance";
}

TEST(SphereIntersect, RayStartingInsideSeesTheFarSide) {
  float t = 0.f;
  ASSERT_TRUE(intersect_sphere(make_ray({0, 0, 0}, {0, 1, 0}), vec3(0.f), 2.f, &t));
  EXPECT_EQ(t, 2.f);
  ASSERT_TRUE(intersect_sphere(make_ray({0, 0.5f, 0}, {0, -1, 0}), vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 1.5f);
}

TEST(SphereIntersect, OpenIntervalTminTmax) {
  const Ray base = make_ray({0, 0, 5}, {0, 0, -1});  // roots 4 and 6
  float t = 0.f;
  Ray r = base;
  r.tmax = 3.9f;
  EXPECT_FALSE(intersect_sphere(r, vec3(0.f), 1.f, &t));
  r.tmax = 4.f;  // open: t = 4 is outside
  EXPECT_FALSE(intersect_sphere(r, vec3(0.f), 1.f, &t));
  r.tmax = 4.5f;
  ASSERT_TRUE(intersect_sphere(r, vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 4.f);
  r = base;
  r.tmin = 4.f;  // open: the near root is excluded, the far one is next
  ASSERT_TRUE(intersect_sphere(r, vec3(0.f), 1.f, &t));
  EXPECT_EQ(t, 6.f);
  r.tmin = 5.f;
  r.tmax = 6.f;
  EXPECT_FALSE(intersect_sphere(r, vec3(0.f), 1.f, &t));
  r.tmin = 6.f;
  r.tmax = infinity;
  EXPECT_FALSE(intersect_sphere(r, vec3(0.f), 1.f, &t));
}

// Exact roots (in double) of the float inputs, by the same stable formulas.
bool reference_roots(vec3 o, vec3 d, vec3 c, float r, double* t0, double* t1) {
  dvec3 f = dvec3(o) - dvec3(c), D(d);
  double a = glm::dot(D, D), b = -glm::dot(f, D), cc = glm::dot(f, f) - double(r) * r;
  dvec3 l = f + (b / a) * D;
  double disc = a * (double(r) * r - glm::dot(l, l));
  if (disc < 0) return false;
  double q = b + std::copysign(std::sqrt(disc), b);
  *t0 = std::min(cc / q, q / a);
  *t1 = std::max(cc / q, q / a);
  return true;
}

TEST(SphereIntersect, RootsMatchDoublePrecisionOverRandomRays) {
  // Spheres from radius e^-5 (small, far away: the case where the textbook
  // b^2 - 4ac form loses every digit) to e^5 (large, origin inside), rays aimed
  // at a point well inside (at most 0.9 r from the centre, so none is grazing).
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int tested = 0;
  double worst = 0.0;
  while (tested < 20000) {
    vec3 c(u(rng) * 100, u(rng) * 100, u(rng) * 100);
    float r = std::exp(u(rng) * 5.f);
    vec3 o(u(rng) * 100, u(rng) * 100, u(rng) * 100);
    vec3 k(u(rng), u(rng), u(rng));
    if (glm::length(k) > 1.f) continue;
    vec3 d = (c + 0.9f * r * k) - o;
    double e0, e1;
    ASSERT_TRUE(reference_roots(o, d, c, r, &e0, &e1));
    float t0, t1;
    ASSERT_TRUE(sphere_roots(o, d, c, r, &t0, &t1)) << "ray aimed inside the sphere reported a miss";
    // Errors relative to the size of the problem, (|o - c| + r) / |d|: a few
    // float roundings in each of f, a, b, c, l, the discriminant and q. 16 unit
    // roundoffs leaves a margin of 3 over the worst seen; the textbook form is
    // off by more than 100 % on the small far spheres.
    double scale = (glm::length(dvec3(o) - dvec3(c)) + r) / glm::length(dvec3(d));
    double err = std::max(std::abs(t0 - e0), std::abs(t1 - e1)) / scale;
    worst = std::max(worst, err);
    ASSERT_LE(err, 16.0 * machine_epsilon) << "sphere c=(" << c.x << "," << c.y << "," << c.z << ") r=" << r;
    ++tested;
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(SphereIntersect, TinySphereFarAwayIsHitWhereItIs) {
  // r = 1e-3 at distance 1e4: the hit point must lie on the sphere.
  const vec3 c(0.f, 0.f, -1.0e4f);
  const float r = 1e-3f;
  float t = 0.f;
  ASSERT_TRUE(intersect_sphere(make_ray({0, 0, 0}, {0, 0, -1}), c, r, &t));
  // t = 1e4 - 1e-3; float spacing at 1e4 is 2^-10 ~ 1e-3: within one spacing.
  EXPECT_NEAR(t, 1.0e4 - 1e-3, 1.0 / 1024.0);
  // Slightly off-axis but still inside: hit; outside by 10 %: miss.
  vec3 in = c + vec3(0.9f * r, 0.f, 0.f), out = c + vec3(1.1f * r, 0.f, 0.f);
  EXPECT_TRUE(intersect_sphere(make_ray({0, 0, 0}, in), c, r, &t));
  EXPECT_FALSE(intersect_sphere(make_ray({0, 0, 0}, out), c, r, &t));
}

}  // namespace
}  // namespace rayform
