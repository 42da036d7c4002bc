// BVH build and traversal (src/accel/bvh.h, mesh_accel.h): the closest hit
// through the BVH equals brute force over every triangle, bit for bit, on a
// random triangle soup and on a closed icosphere; the any-hit query agrees
// with brute force on segments; and the tree is well formed.
#include "accel/mesh_accel.h"
#include "scene/procedural_mesh.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstring>
#include <random>

namespace rayform {
namespace {

struct SoupMesh {
  std::vector<vec3> positions;
  std::vector<uint32_t> indices;
};

// n triangles of edge up to `size` with centres uniform in [-10, 10]^3.
SoupMesh random_soup(int n, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> c(-10.f, 10.f), e(-1.f, 1.f);
  SoupMesh m;
  for (int i = 0; i < n; ++i) {
    vec3 centre(c(rng), c(rng), c(rng));
    for (int k = 0; k < 3; ++k) {
      m.positions.push_back(centre + size * vec3(e(rng), e(rng), e(rng)));
      m.indices.push_back(uint32_t(m.positions.size() - 1));
    }
  }
  return m;
}

struct BruteHit {
  bool hit = false;
  float t = infinity;
  uint32_t triangle = 0;
  TriangleHit th{};
};

// Every triangle in index order, with the same kernel and per-ray constants.
BruteHit brute_closest(std::span<const vec3> pos, std::span<const uint32_t> idx, const Ray& ray) {
  const TriangleRay tr = make_triangle_ray(ray);
  BruteHit best;
  float tmax = ray.tmax;
  for (uint32_t t = 0; t < idx.size() / 3; ++t) {
    TriangleHit h;
    if (intersect_triangle(tr, pos[idx[3 * t]], pos[idx[3 * t + 1]], pos[idx[3 * t + 2]], ray.tmin, tmax, &h)) {
      tmax = h.t;
      best = {true, h.t, t, h};
    }
  }
  return best;
}

Ray random_ray(std::mt19937& rng, float extent) {
  std::uniform_real_distribution<float> o(-extent, extent), d(-1.f, 1.f);
  Ray r;
  r.origin = vec3(o(rng), o(rng), o(rng));
  do r.direction = vec3(d(rng), d(rng), d(rng));
  while (glm::length(r.direction) < 0.1f);
  return r;
}

// Compares the BVH's closest hit with brute force for one ray.
void expect_same_closest(std::span<const vec3> pos, std::span<const uint32_t> idx, const MeshAccel& accel,
                         const Ray& ray, int* hits) {
  BruteHit want = brute_closest(pos, idx, ray);
  float tmax = ray.tmax;
  MeshHit got{};
  bool hit = intersect_mesh(accel, ray, tmax, &got);
  ASSERT_EQ(hit, want.hit);
  if (!hit) {
    EXPECT_EQ(tmax, ray.tmax) << "a miss must leave tmax alone";
    return;
  }
  ++*hits;
  // Same kernel, same inputs: the same float, not merely close.
  ASSERT_EQ(tmax, want.t);
  if (got.triangle != want.triangle) {
    // A tie between two triangles at the same distance: either is right.
    TriangleHit other;
    const TriangleRay tr = make_triangle_ray(ray);
    ASSERT_TRUE(intersect_triangle(tr, pos[idx[3 * got.triangle]], pos[idx[3 * got.triangle + 1]],
                                   pos[idx[3 * got.triangle + 2]], ray.tmin, ray.tmax, &other));
    ASSERT_EQ(other.t, want.t);
    return;
  }
  EXPECT_EQ(got.b0, want.th.b0);
  EXPECT_EQ(got.b1, want.th.b1);
  EXPECT_EQ(got.b2, want.th.b2);
}

TEST(Bvh, ClosestHitEqualsBruteForceOnRandomSoup) {
  SoupMesh m = random_soup(3000, 1.5f, 1);
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  ASSERT_EQ(accel.triangles.size(), 3000u);
  std::mt19937 rng(2);
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    Ray r = random_ray(rng, 15.f);
    expect_same_closest(m.positions, m.indices, accel, r, &hits);
    if (HasFatalFailure()) FAIL() << "ray " << i;
  }
  EXPECT_GT(hits, 1000) << "too few hits for the comparison to mean much";
}

TEST(Bvh, ClosestHitEqualsBruteForceWithOtherBuildOptions) {
  SoupMesh m = random_soup(1500, 2.f, 3);
  for (BvhBuildOptions o : {BvhBuildOptions{1, 16, 1.f}, BvhBuildOptions{8, 2, 1.f}, BvhBuildOptions{4, 32, 4.f}}) {
    MeshAccel accel = build_mesh_accel(m.positions, m.indices, o);
    std::mt19937 rng(4);
    int hits = 0;
    for (int i = 0; i < 1500; ++i) {
      Ray r = random_ray(rng, 15.f);
      if (i % 3 == 0) r.tmax = 8.f;  // segments too
      if (i % 5 == 0) r.tmin = 2.f;
      expect_same_closest(m.positions, m.indices, accel, r, &hits);
      if (HasFatalFailure()) FAIL() << "leaf size " << o.max_leaf_size << " bins " << o.bins << " ray " << i;
    }
    EXPECT_GT(hits, 300);
  }
}

TEST(Bvh, ClosestHitEqualsBruteForceOnIcosphere) {
  Mesh m = make_icosphere(4);
  ASSERT_EQ(m.triangle_count(), 20u * 256u);
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> s(-1.f, 1.f);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray r;
    if (i % 2) {
      r = random_ray(rng, 3.f);  // from outside or inside, any direction
    } else {
      // Aimed at a random point on the sphere from outside.
      r.origin = glm::normalize(vec3(s(rng), s(rng), s(rng)) + vec3(1e-3f)) * 4.f;
      r.direction = vec3(s(rng), s(rng), s(rng)) * 0.9f - r.origin;
    }
    expect_same_closest(m.positions, m.indices, accel, r, &hits);
    if (HasFatalFailure()) FAIL() << "ray " << i;
  }
  EXPECT_GT(hits, 1000) << "too few hits for the comparison to mean much";
}

TEST(Bvh, RaysFromInsideAClosedMeshAlwaysHit) {
  // The icosphere is closed and watertight: every ray from inside hits, at a
  // distance between the inscribed radius and 1 (level 3: the faces lie at
  // least cos(half the largest edge angle) ~ 0.98 from the centre).
  Mesh m = make_icosphere(3);
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> s(-1.f, 1.f);
  for (int i = 0; i < 5000; ++i) {
    Ray r;
    r.origin = vec3(0.f);
    do r.direction = vec3(s(rng), s(rng), s(rng));
    while (glm::length(r.direction) < 0.1f);
    r.direction = glm::normalize(r.direction);
    float tmax = infinity;
    MeshHit h{};
    ASSERT_TRUE(intersect_mesh(accel, r, tmax, &h)) << "ray " << i << " escaped the closed sphere";
    EXPECT_GT(tmax, 0.98f);
    // Never beyond the circumscribed unit sphere; 1e-6 (8 ulps at 1) covers the
    // rounding of the normalised vertices and of t.
    EXPECT_LE(tmax, 1.f + 1e-6f);
  }
}

TEST(Bvh, AnyHitAgreesWithBruteForce) {
  SoupMesh m = random_soup(2000, 1.f, 7);
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  Mesh sphere = make_icosphere(3);
  MeshAccel sphere_accel = build_mesh_accel(sphere.positions, sphere.indices);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> len(0.f, 30.f);
  int blocked = 0, free = 0;
  for (int i = 0; i < 4000; ++i) {
    Ray r = random_ray(rng, 15.f);
    r.tmax = len(rng);  // shadow-ray segments of every length
    bool want = brute_closest(m.positions, m.indices, r).hit;
    ASSERT_EQ(occluded_mesh(accel, r), want) << "ray " << i;
    (want ? blocked : free)++;
    Ray rs = random_ray(rng, 2.f);
    rs.tmax = len(rng) / 10.f;
    ASSERT_EQ(occluded_mesh(sphere_accel, rs), brute_closest(sphere.positions, sphere.indices, rs).hit) << "ray " << i;
  }
  EXPECT_GT(blocked, 200);
  EXPECT_GT(free, 200);
}

TEST(Bvh, CoincidentTrianglesStillFindTheHit) {
  // 500 copies of one triangle: no plane separates the centroids.
  SoupMesh m;
  m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
  for (int i = 0; i < 500; ++i) m.indices.insert(m.indices.end(), {0, 1, 2});
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  Ray r;
  r.origin = vec3(0.2f, 0.2f, 1.f);
  r.direction = vec3(0, 0, -1);
  float tmax = infinity;
  MeshHit h{};
  ASSERT_TRUE(intersect_mesh(accel, r, tmax, &h));
  EXPECT_EQ(tmax, 1.f);
  EXPECT_LT(h.triangle, 500u);
  EXPECT_TRUE(occluded_mesh(accel, r));
}

// Walks the flattened tree and checks its invariants; returns the depth.
int check_subtree(const Bvh& bvh, uint32_t index, std::span<const Bounds3> prims, int max_leaf,
                  std::vector<int>& seen) {
  const BvhNode& n = bvh.nodes.at(index);
  if (n.count > 0) {
    EXPECT_LE(int(n.count), max_leaf);
    for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
      uint32_t id = bvh.primitives.at(i);
      seen.at(id)++;
      const Bounds3& b = prims[id];
      EXPECT_TRUE(glm::all(glm::lessThanEqual(n.lo, b.lo)) && glm::all(glm::greaterThanEqual(n.hi, b.hi)))
          << "leaf " << index << " does not enclose primitive " << id;
    }
    return 1;
  }
  EXPECT_LT(n.axis, 3);
  uint32_t left = index + 1, right = n.offset;
  EXPECT_GT(right, left) << "depth-first layout: the right child follows the left subtree";
  for (uint32_t c : {left, right}) {
    const BvhNode& ch = bvh.nodes.at(c);
    EXPECT_TRUE(glm::all(glm::lessThanEqual(n.lo, ch.lo)) && glm::all(glm::greaterThanEqual(n.hi, ch.hi)))
        << "node " << index << " does not enclose child " << c;
  }
  return 1 +
         std::max(check_subtree(bvh, left, prims, max_leaf, seen), check_subtree(bvh, right, prims, max_leaf, seen));
}

TEST(Bvh, TreeIsWellFormed) {
  SoupMesh m = random_soup(2000, 1.f, 9);
  std::vector<Bounds3> prims(m.indices.size() / 3);
  for (size_t t = 0; t < prims.size(); ++t)
    for (int k = 0; k < 3; ++k) prims[t].expand(m.positions[m.indices[3 * t + k]]);
  // Two primitives with empty bounds (and one non-finite) are left out.
  prims[10] = Bounds3{};
  prims[20] = Bounds3{};
  prims[30].hi.x = infinity;
  for (int leaf : {1, 4, 8}) {
    BvhBuildOptions o;
    o.max_leaf_size = leaf;
    Bvh bvh = build_bvh(prims, o);
    ASSERT_FALSE(bvh.nodes.empty());
    std::vector<int> seen(prims.size(), 0);
    int depth = check_subtree(bvh, 0, prims, leaf, seen);
    EXPECT_LE(depth, bvh_max_depth);
    for (size_t i = 0; i < prims.size(); ++i) {
      int want = (i == 10 || i == 20 || i == 30) ? 0 : 1;
      EXPECT_EQ(seen[i], want) << "primitive " << i << " with leaf size " << leaf;
    }
    EXPECT_EQ(bvh.primitives.size(), prims.size() - 3);
  }
  EXPECT_TRUE(build_bvh(std::vector<Bounds3>{}).nodes.empty());
}

// Byte images of the structure (nodes and packets have no padding bytes that
// the builder leaves unwritten: the static_asserts fix their layout).
template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

TEST(Bvh, BuildIsDeterministic) {
  // Large enough for the parallel builder to split work between threads.
  SoupMesh m = random_soup(200000, 1.f, 10);
  MeshAccel a = build_mesh_accel(m.positions, m.indices), b = build_mesh_accel(m.positions, m.indices);
  MeshAccel one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = build_mesh_accel(m.positions, m.indices);
  }
  ASSERT_GT(a.bvh.nodes.size(), 1000u);
  EXPECT_TRUE(same_bytes(a.bvh.nodes, b.bvh.nodes)) << "the same input must give the same nodes";
  EXPECT_TRUE(same_bytes(a.packets, b.packets));
  EXPECT_EQ(a.triangles, b.triangles) << "the same input must give the same leaf order";
  EXPECT_TRUE(same_bytes(a.bvh.nodes, one.bvh.nodes)) << "one thread must build what several build";
  EXPECT_TRUE(same_bytes(a.packets, one.packets));
  EXPECT_EQ(a.triangles, one.triangles);
  Bvh x = build_bvh(std::vector<Bounds3>(1, Bounds3{vec3(0.f), vec3(1.f)}));
  EXPECT_EQ(x.nodes.size(), 1u);
  EXPECT_EQ(x.primitives, std::vector<uint32_t>{0});
}

}  // namespace
}  // namespace rayform
