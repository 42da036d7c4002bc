// Ray/plane intersection (src/geometry/plane_intersect.h): the plane
// n . p = d with n of any length, both sides, parallel rays, (tmin, tmax).
#include "rayform/geometry/plane_intersect.h"
#include "test_rays.h"

#include <gtest/gtest.h>

#include <random>

namespace rayform {
namespace {

using test::make_ray;

TEST(PlaneIntersect, HitFromAbove) {
  // The course's floor: normal 0 1 0, offset -2 (y = -2).
  float t = 0.f;
  ASSERT_TRUE(intersect_plane(make_ray({0, 0, 0}, {0, -1, 0}), vec3(0, 1, 0), -2.f, &t));
  EXPECT_EQ(t, 2.f);
  ASSERT_TRUE(intersect_plane(make_ray({3, 1, -7}, {0, -2, 0}), vec3(0, 1, 0), -2.f, &t));
  EXPECT_EQ(t, 1.5f);  // units of |d|
}

TEST(PlaneIntersect, SlantedRayHitPointLiesOnThePlane) {
  float t = 0.f;
  Ray r = make_ray({0, 10, 0}, {3, -4, 0});
  ASSERT_TRUE(intersect_plane(r, vec3(0, 1, 0), -2.f, &t));
  EXPECT_EQ(t, 3.f);
  EXPECT_EQ(r.at(t), vec3(9, -2, 0));
}

TEST(PlaneIntersect, BackSideIsHitToo) {
  float t = 0.f;
  ASSERT_TRUE(intersect_plane(make_ray({0, -5, 0}, {0, 1, 0}), vec3(0, 1, 0), -2.f, &t));
  EXPECT_EQ(t, 3.f);
}

TEST(PlaneIntersect, NormalOfAnyLengthGivesTheSamePlane) {
  // 0 2 0 . p = -4 is the plane y = -2 again.
  float t = 0.f;
  ASSERT_TRUE(intersect_plane(make_ray({0, 0, 0}, {0, -1, 0}), vec3(0, 2, 0), -4.f, &t));
  EXPECT_EQ(t, 2.f);
  // A tilted normal 1 1 0 with offset 2: x + y = 2; from the origin along +x.
  ASSERT_TRUE(intersect_plane(make_ray({0, 0, 0}, {1, 0, 0}), vec3(1, 1, 0), 2.f, &t));
  EXPECT_EQ(t, 2.f);
}

TEST(PlaneIntersect, ParallelAndReceedingRaysMiss) {
  float t = 42.f;
  EXPECT_FALSE(intersect_plane(make_ray({0, 0, 0}, {1, 0, 0}), vec3(0, 1, 0), -2.f, &t));   // parallel
  EXPECT_FALSE(intersect_plane(make_ray({0, -2, 0}, {1, 0, 0}), vec3(0, 1, 0), -2.f, &t));  // in the plane
  EXPECT_FALSE(intersect_plane(make_ray({0, 0, 0}, {0, 1, 0}), vec3(0, 1, 0), -2.f, &t));   // going away
  EXPECT_EQ(t, 42.f) << "a miss must not write the hit distance";
}

TEST(PlaneIntersect, OpenIntervalTminTmax) {
  float t = 0.f;
  const Ray base = make_ray({0, 0, 0}, {0, -1, 0});  // hit at 2
  Ray r = base;
  r.tmax = 2.f;
  EXPECT_FALSE(intersect_plane(r, vec3(0, 1, 0), -2.f, &t));
  r.tmax = std::nextafter(2.f, 3.f);
  EXPECT_TRUE(intersect_plane(r, vec3(0, 1, 0), -2.f, &t));
  r = base;
  r.tmin = 2.f;
  EXPECT_FALSE(intersect_plane(r, vec3(0, 1, 0), -2.f, &t));
  r.tmin = std::nextafter(2.f, 1.f);
  EXPECT_TRUE(intersect_plane(r, vec3(0, 1, 0), -2.f, &t));
}

TEST(PlaneIntersect, GrazingRaysStayAccurate) {
  // t = (d - n.o) / (n.dir): each dot product is within gamma(3) |n||v| of
  // its exact value, the subtraction and the division add one rounding each.
  // So against a double evaluation of the same float inputs
  //   |t - exact| <~ 5u |t| + 3u |t| |n||dir| / |n.dir| + 3u (|d| + |n||o|) / |n.dir|;
  // we allow 8u on each term. The tilt keeps |n.dir| >= 2^-13, far above the
  // rounding of the dot product, so hit and miss are never confused.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int tested = 0;
  while (tested < 20000) {
    vec3 n = glm::normalize(vec3(u(rng), u(rng), u(rng)));
    float d = u(rng) * 10.f;
    vec3 o(u(rng) * 10, u(rng) * 10, u(rng) * 10);
    // A direction almost parallel to the plane: the tangent part plus a tiny
    // normal component of either sign.
    vec3 tangent = glm::normalize(glm::cross(n, vec3(u(rng), u(rng), u(rng))));
    float tilt = std::copysign(std::ldexp(0.5f + 0.5f * std::abs(u(rng)), -int(rng() % 12)), u(rng));
    vec3 dir = tangent + tilt * n;
    double dn = glm::dot(dvec3(n), dvec3(dir));
    double num = double(d) - glm::dot(dvec3(n), dvec3(o));
    double exact = num / dn;
    float t = 0.f;
    bool hit = intersect_plane(make_ray(o, dir), n, d, &t);
    if (std::abs(exact) < 1e-3) continue;  // too close to the origin to classify
    ASSERT_EQ(hit, exact > 0.0) << "exact t = " << exact;
    if (!hit) {
      ++tested;
      continue;
    }
    double den_scale = std::abs(exact) * glm::length(dvec3(dir)) / std::abs(dn);
    double num_scale = (std::abs(double(d)) + glm::length(dvec3(o))) / std::abs(dn);
    double bound = 8.0 * machine_epsilon * (std::abs(exact) + den_scale + num_scale);
    ASSERT_NEAR(t, exact, bound);
    ++tested;
  }
}

}  // namespace
}  // namespace rayform
