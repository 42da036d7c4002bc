// Eight rays at once through a MeshAccel (intersect_mesh8): each ray gets
// exactly the hit intersect_mesh gives it, bit for bit, for coherent camera
// bundles, for random rays (mixed octants: the one-by-one path; one octant:
// the packet path), for partial packets, and for rays through shared edges
// and vertices, where triangles tie at equal t and the winner must not depend
// on the order the traversal meets them in.
#include "rayform/accel/mesh_accel.h"
#include "rayform/scene/procedural_mesh.h"

#include <gtest/gtest.h>

#include <random>

namespace rayform {
namespace {

struct Result {
  int found = 0;
  float tmax[8];
  MeshHit hits[8];
};

Result single(const MeshAccel& m, const Ray* rays, int active) {
  Result r;
  for (int i = 0; i < 8; ++i) {
    r.tmax[i] = rays[i].tmax;
    r.hits[i] = {};
    if (((active >> i) & 1) && intersect_mesh(m, rays[i], r.tmax[i], &r.hits[i])) r.found |= 1 << i;
  }
  return r;
}

Result packet(const MeshAccel& m, const Ray* rays, int active) {
  Result r;
  for (int i = 0; i < 8; ++i) {
    r.tmax[i] = rays[i].tmax;
    r.hits[i] = {};
  }
  r.found = intersect_mesh8(m, rays, active, r.tmax, r.hits);
  return r;
}

// Returns how many rays hit.
int expect_identical(const MeshAccel& m, const Ray* rays, int active, const char* what) {
  const Result a = single(m, rays, active), b = packet(m, rays, active);
  EXPECT_EQ(a.found, b.found) << what;
  int hits = 0;
  for (int i = 0; i < 8; ++i) {
    if (!((active >> i) & 1)) continue;
    EXPECT_EQ(a.tmax[i], b.tmax[i]) << what << " ray " << i;
    if (!((a.found >> i) & 1)) continue;
    ++hits;
    EXPECT_EQ(a.hits[i].triangle, b.hits[i].triangle) << what << " ray " << i;
    EXPECT_EQ(a.hits[i].b0, b.hits[i].b0) << what << " ray " << i;
    EXPECT_EQ(a.hits[i].b1, b.hits[i].b1) << what << " ray " << i;
    EXPECT_EQ(a.hits[i].b2, b.hits[i].b2) << what << " ray " << i;
  }
  return hits;
}

// Rays of a pinhole camera at `eye` looking at the origin, in rows of 8 pixels.
std::vector<Ray> camera_rays(vec3 eye, int width, int height) {
  const vec3 w = glm::normalize(-eye), u = glm::normalize(glm::cross(w, vec3(0, 1, 0))), v = glm::cross(u, w);
  std::vector<Ray> rays;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Ray r;
      r.origin = eye;
      const float px = 2.f * float(x) / float(width - 1) - 1.f, py = 2.f * float(y) / float(height - 1) - 1.f;
      r.direction = glm::normalize(0.6f * px * u + 0.6f * py * v + w);
      rays.push_back(r);
    }
  return rays;
}

TEST(MeshPacket, CameraBundlesEqualSingleRays) {
  const Mesh torus = make_bumpy_torus(20000, 3);
  const MeshAccel m = build_mesh_accel(torus.positions, torus.indices);
  int hits = 0;
  for (vec3 eye : {vec3(0.3f, 2.f, 3.f), vec3(-2.f, -1.5f, 2.5f), vec3(0.f, 0.f, -4.f)}) {
    const std::vector<Ray> rays = camera_rays(eye, 64, 48);
    for (size_t i = 0; i < rays.size(); i += 8) hits += expect_identical(m, &rays[i], 0xff, "camera");
  }
  EXPECT_GT(hits, 1200);  // the torus covers about a sixth of each view
}

TEST(MeshPacket, RandomRaysAndPartialPacketsEqualSingleRays) {
  const Mesh torus = make_bumpy_torus(5000, 7);
  const MeshAccel m = build_mesh_accel(torus.positions, torus.indices);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> o(-2.f, 2.f), d(-1.f, 1.f);
  std::uniform_int_distribution<int> mask(1, 255);
  int hits = 0;
  for (int n = 0; n < 2000; ++n) {
    Ray rays[8];
    const bool one_octant = n % 2 == 1;
    for (Ray& r : rays) {
      r.origin = vec3(o(rng), o(rng), o(rng));
      r.direction = vec3(d(rng), d(rng), d(rng));
      if (one_octant) r.direction = glm::abs(r.direction) * vec3(1, -1, 1) + vec3(0.01f, -0.01f, 0.01f);
      if (n % 5 == 0) r.tmax = 1.5f;  // bounded segments too
    }
    hits += expect_identical(m, rays, n % 3 == 0 ? mask(rng) : 0xff, one_octant ? "one octant" : "mixed");
  }
  EXPECT_GT(hits, 1500);
}

// A flat grid of 2 x 32 x 32 triangles in z = 0 and rays straight down onto
// its vertices and edge midpoints: every such ray hits 2 to 6 triangles at
// exactly the same t. Single rays and packets meet them in different orders.
TEST(MeshPacket, TiesOnSharedEdgesAndVerticesPickTheSameTriangle) {
  std::vector<vec3> positions;
  std::vector<uint32_t> indices;
  const int n = 32;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) positions.push_back(vec3(float(x) / 4.f, float(y) / 4.f, 0.f));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), e = c + 1;
      indices.insert(indices.end(), {a, b, e, a, e, c});
    }
  const MeshAccel m = build_mesh_accel(positions, indices);
  int hits = 0;
  for (int y = 1; y < 2 * n - 1; ++y)
    for (int x0 = 1; x0 + 8 < 2 * n; x0 += 8) {
      Ray rays[8];
      for (int i = 0; i < 8; ++i) {
        rays[i].origin = vec3(float(x0 + i) / 8.f, float(y) / 8.f, 2.f);  // vertices and edge midpoints
        rays[i].direction = vec3(0.f, 0.f, -1.f);
      }
      hits += expect_identical(m, rays, 0xff, "grid");
    }
  EXPECT_GT(hits, 3000);
}

}  // namespace
}  // namespace rayform
