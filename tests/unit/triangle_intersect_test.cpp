// Watertight ray/triangle intersection (src/geometry/triangle_intersect.h):
// hits, misses, barycentrics, (tmin, tmax), both faces, degenerate
// triangles, and rays through an edge or a vertex shared by two or more
// triangles, which must hit at least one of them.
#include "rayform/geometry/triangle_intersect.h"
#include "test_rays.h"

#include <gtest/gtest.h>

#include <random>

namespace rayform {
namespace {

using test::make_ray;

const vec3 P0(0, 0, 0), P1(1, 0, 0), P2(0, 1, 0);

TEST(TriangleIntersect, HitWithBarycentrics) {
  TriangleHit h{};
  ASSERT_TRUE(intersect_triangle(make_ray({0.25f, 0.5f, 2}, {0, 0, -1}), P0, P1, P2, &h));
  EXPECT_EQ(h.t, 2.f);
  // Point = b0 p0 + b1 p1 + b2 p2 = (b1, b2, 0): b1 = 0.25, b2 = 0.5.
  EXPECT_EQ(h.b0, 0.25f);
  EXPECT_EQ(h.b1, 0.25f);
  EXPECT_EQ(h.b2, 0.5f);
}

TEST(TriangleIntersect, BarycentricsReproduceTheHitPoint) {
  const vec3 a(1, 2, 3), b(4, -1, 2), c(-2, 0, 5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.05f, 0.9f);
  for (int i = 0; i < 1000; ++i) {
    float w1 = u(rng), w2 = u(rng) * (1.f - w1);
    vec3 target = (1.f - w1 - w2) * a + w1 * b + w2 * c;
    vec3 o(10.f * u(rng), -10.f * u(rng), 12.f);
    TriangleHit h{};
    Ray r = make_ray(o, target - o);
    ASSERT_TRUE(intersect_triangle(r, a, b, c, &h)) << i;
    // Three quotients e_k / det, each rounded once, and their float sum.
    EXPECT_NEAR(h.b0 + h.b1 + h.b2, 1.0, 4 * machine_epsilon);
    // Both are within a few float roundings of the target (coordinates <= 20):
    // 1e-5 is ~80 roundings of 2^-24 * 20, far below a wrong barycentric.
    vec3 from_bary = h.b0 * a + h.b1 * b + h.b2 * c;
    vec3 from_t = r.at(h.t);
    EXPECT_NEAR(h.t, 1.f, 1e-5f);
    EXPECT_NEAR(h.b1, w1, 1e-5f);
    EXPECT_NEAR(h.b2, w2, 1e-5f);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(from_bary[k], target[k], 1e-5f);
      EXPECT_NEAR(from_t[k], target[k], 1e-5f);
    }
  }
}

TEST(TriangleIntersect, BothFacesAreHit) {
  TriangleHit h{};
  ASSERT_TRUE(intersect_triangle(make_ray({0.25f, 0.25f, -3}, {0, 0, 1}), P0, P1, P2, &h));
  EXPECT_EQ(h.t, 3.f);
}

TEST(TriangleIntersect, Misses) {
  TriangleHit h{};
  h.t = 77.f;
  EXPECT_FALSE(intersect_triangle(make_ray({0.6f, 0.6f, 1}, {0, 0, -1}), P0, P1, P2, &h));   // beyond the hypotenuse
  EXPECT_FALSE(intersect_triangle(make_ray({-0.1f, 0.5f, 1}, {0, 0, -1}), P0, P1, P2, &h));  // left of x = 0
  EXPECT_FALSE(intersect_triangle(make_ray({0.5f, -0.1f, 1}, {0, 0, -1}), P0, P1, P2, &h));  // below y = 0
  EXPECT_FALSE(intersect_triangle(make_ray({0.2f, 0.2f, 1}, {0, 0, 1}), P0, P1, P2, &h));    // pointing away
  EXPECT_FALSE(intersect_triangle(make_ray({-1, 0.2f, 0}, {1, 0, 0}), P0, P1, P2, &h));      // in its plane, edge-on
  EXPECT_EQ(h.t, 77.f) << "a miss must not write the hit";
}

TEST(TriangleIntersect, DegenerateTrianglesAreNeverHit) {
  TriangleHit h{};
  // Collinear vertices, and all three equal.
  EXPECT_FALSE(intersect_triangle(make_ray({0.5f, 0, 1}, {0, 0, -1}), vec3(0, 0, 0), vec3(1, 0, 0), vec3(2, 0, 0), &h));
  EXPECT_FALSE(intersect_triangle(make_ray({0, 0, 1}, {0, 0, -1}), vec3(0.f), vec3(0.f), vec3(0.f), &h));
}

TEST(TriangleIntersect, OpenIntervalTminTmax) {
  TriangleHit h{};
  const Ray base = make_ray({0.2f, 0.2f, 4}, {0, 0, -1});  // t = 4
  Ray r = base;
  r.tmax = 4.f;
  EXPECT_FALSE(intersect_triangle(r, P0, P1, P2, &h));
  r.tmax = std::nextafter(4.f, 5.f);
  ASSERT_TRUE(intersect_triangle(r, P0, P1, P2, &h));
  EXPECT_EQ(h.t, 4.f);
  r = base;
  r.tmin = 4.f;
  EXPECT_FALSE(intersect_triangle(r, P0, P1, P2, &h));
  r.tmin = 3.f;
  EXPECT_TRUE(intersect_triangle(r, P0, P1, P2, &h));
  // The precomputed form takes tmin and tmax explicitly.
  TriangleRay tr = make_triangle_ray(base);
  EXPECT_FALSE(intersect_triangle(tr, P0, P1, P2, 0.f, 3.5f, &h));
  EXPECT_TRUE(intersect_triangle(tr, P0, P1, P2, 0.f, 4.5f, &h));
  EXPECT_EQ(h.t, 4.f);
}

TEST(TriangleIntersect, DirectionComponentsOfEitherSignAndAxis) {
  // The test permutes axes by the largest direction component; exercise all three.
  const vec3 a(0, 0, 0);
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.f, 1.f}) {
      vec3 e1(0.f), e2(0.f), d(0.f), o(0.f);
      e1[(axis + 1) % 3] = 1.f;
      e2[(axis + 2) % 3] = 1.f;
      d[axis] = sign;
      o[axis] = -3.f * sign;
      o += 0.25f * e1 + 0.25f * e2;
      TriangleHit h{};
      ASSERT_TRUE(intersect_triangle(make_ray(o, d), a, a + e1, a + e2, &h)) << axis << " " << sign;
      EXPECT_EQ(h.t, 3.f);
      EXPECT_EQ(h.b1, 0.25f);
      EXPECT_EQ(h.b2, 0.25f);
    }
}

// A quad split along its diagonal: rays aimed at points of the shared edge
// hit at least one of the two triangles; rays aimed inside one triangle hit
// exactly that one.
TEST(TriangleIntersect, SharedEdgeIsWatertight) {
  const vec3 a(-1.3f, -0.7f, 0.2f), b(1.1f, -0.9f, -0.3f), c(0.9f, 1.2f, 0.4f), d(-1.2f, 0.8f, -0.1f);
  // Triangles (a, b, c) and (a, c, d) share the edge a-c.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f), s(-1.f, 1.f);
  int lost = 0, both = 0;
  for (int i = 0; i < 20000; ++i) {
    float w = u(rng);
    vec3 on_edge = a + w * (c - a);  // rounded: lies within an ulp of the edge
    vec3 o = vec3(s(rng), s(rng), 0.f) * 5.f + vec3(0, 0, 4.f + 3.f * u(rng)) * (i % 2 ? 1.f : -1.f);
    const TriangleRay tr = make_triangle_ray(make_ray(o, on_edge - o));
    TriangleHit h{};
    bool h1 = intersect_triangle(tr, a, b, c, 0.f, infinity, &h);
    bool h2 = intersect_triangle(tr, a, c, d, 0.f, infinity, &h);
    lost += !h1 && !h2;
    both += h1 && h2;
  }
  EXPECT_EQ(lost, 0) << "rays through the shared edge slipped between the triangles";
  RecordProperty("rays_hitting_both", both);
}

TEST(TriangleIntersect, InteriorRaysHitExactlyOneOfTwoNeighbours) {
  const vec3 a(-1, -1, 0), b(1, -1, 0), c(1, 1, 0), d(-1, 1, 0);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> s(-0.95f, 0.95f);
  for (int i = 0; i < 2000; ++i) {
    vec3 p(s(rng), s(rng), 0.f);
    if (std::abs(p.x - p.y) < 1e-3f) continue;  // away from the diagonal
    TriangleHit h{};
    Ray r = make_ray(p + vec3(0.1f, -0.2f, 3.f), vec3(-0.1f, 0.2f, -3.f));
    bool h1 = intersect_triangle(r, a, b, c, &h), h2 = intersect_triangle(r, a, c, d, &h);
    ASSERT_NE(h1, h2) << "point " << p.x << "," << p.y;
    EXPECT_EQ(h1, p.x > p.y);
  }
}

TEST(TriangleIntersect, SharedVertexOfAFanIsWatertight) {
  // Eight triangles around the vertex v; rays aimed exactly at v (from both
  // sides, any direction) must hit at least one of them.
  const vec3 v(0.3f, -0.2f, 0.1f);
  std::vector<vec3> rim;
  for (int k = 0; k < 8; ++k) {
    float ang = 2.f * pi * float(k) / 8.f + 0.1f;
    rim.push_back(v + vec3(std::cos(ang), std::sin(ang), 0.05f * float(k % 3)));
  }
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> s(-1.f, 1.f);
  int lost = 0;
  for (int i = 0; i < 5000; ++i) {
    vec3 o = v + vec3(s(rng) * 3.f, s(rng) * 3.f, (i % 2 ? 1.f : -1.f) * (1.f + std::abs(s(rng)) * 4.f));
    const TriangleRay tr = make_triangle_ray(make_ray(o, v - o));
    bool any = false;
    for (int k = 0; k < 8; ++k) {
      TriangleHit h{};
      any |= intersect_triangle(tr, v, rim[k], rim[(k + 1) % 8], 0.f, infinity, &h);
    }
    lost += !any;
  }
  EXPECT_EQ(lost, 0) << "rays through the shared vertex slipped between the triangles";
}

TEST(TriangleIntersect, TDistanceMatchesDoubleReference) {
  // t against the exact plane intersection (double, from the same float
  // inputs). The watertight test translates, permutes and shears the vertices
  // in float: like moving them by a few roundings of |p - o|, which moves t by
  // that much over |d| and over the cosine between the ray and the normal
  // (pbrt-v4 6.8.7). We allow 64 u of (|o| + max |p|) / (|d| cos).
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> s(-1.f, 1.f), u(0.f, 1.f);
  for (int i = 0; i < 5000; ++i) {
    vec3 a(s(rng), s(rng), s(rng)), b(s(rng), s(rng), s(rng)), c(s(rng), s(rng), s(rng));
    a *= 10.f;
    b *= 10.f;
    c *= 10.f;
    float w1 = 0.05f + 0.9f * u(rng), w2 = (0.05f + 0.9f * u(rng)) * (1.f - w1);
    vec3 target = (1.f - w1 - w2) * a + w1 * b + w2 * c;
    vec3 o = vec3(s(rng), s(rng), s(rng)) * 30.f;
    vec3 d = target - o;
    dvec3 n = glm::cross(dvec3(b) - dvec3(a), dvec3(c) - dvec3(a));
    double dn = glm::dot(n, dvec3(d));
    double cosine = std::abs(dn) / (glm::length(n) * glm::length(dvec3(d)));
    if (cosine < 1e-2) continue;  // grazing
    double exact = glm::dot(n, dvec3(a) - dvec3(o)) / dn;
    TriangleHit h{};
    ASSERT_TRUE(intersect_triangle(make_ray(o, d), a, b, c, &h)) << i;
    double scale = (glm::length(dvec3(o)) + 10.0 * std::sqrt(3.0)) / (glm::length(dvec3(d)) * cosine);
    ASSERT_NEAR(h.t, exact, 64.0 * machine_epsilon * scale) << i;
  }
}

}  // namespace
}  // namespace rayform
