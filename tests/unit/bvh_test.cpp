// BVH build and traversal (src/accel/bvh.h, mesh_accel.h): the closest hit
// through the BVH equals brute force over every triangle, bit for bit, on a
// random triangle soup and on a closed icosphere; the any-hit query agrees
// with brute force on segments; and the tree is well formed.
#include "rayform/accel/mesh_accel.h"
#include "rayform/scene/procedural_mesh.h"
#include "test_bytes.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>

namespace rayform {
namespace {

using test::same_bytes;

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

// Walks a mesh tree from node `index` and checks its invariants: children
// after their parent, every child box enclosing what lies below it, leaves of
// at most max_leaf_packets packets. Counts in seen[t] the leaves holding
// triangle t; returns the levels of nodes.
int check_wide_subtree(const MeshAccel& m, std::span<const vec3> pos, std::span<const uint32_t> idx, uint32_t index,
                       std::vector<int>& seen) {
  const WideBvhNode& n = m.bvh.nodes.at(index);
  int depth = 0;
  for (int c = 0; c < WideBvhNode::width; ++c) {
    const vec3 lo(n.bounds[0][c], n.bounds[2][c], n.bounds[4][c]), hi(n.bounds[1][c], n.bounds[3][c], n.bounds[5][c]);
    const uint32_t ref = n.child[c];
    if (lo.x > hi.x) {  // an unused slot
      EXPECT_EQ(WideBvhNode::leaf_packet_count(ref), 0u);
      continue;
    }
    auto inside = [&](const vec3& p) {
      return glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi));
    };
    if (WideBvhNode::is_leaf(ref)) {
      const uint32_t first = WideBvhNode::leaf_first_packet(ref), count = WideBvhNode::leaf_packet_count(ref);
      EXPECT_GE(count, 1u);
      EXPECT_LE(size_t(first) + count, m.packets.size());
      std::vector<uint32_t> ids;
      for (uint32_t k = first; k < first + count && k < m.packets.size(); ++k)
        for (uint32_t id : m.packets[k].id) {
          EXPECT_TRUE(inside(pos[idx[3 * id]]) && inside(pos[idx[3 * id + 1]]) && inside(pos[idx[3 * id + 2]]))
              << "node " << index << " child " << c << " does not enclose triangle " << id;
          if (ids.empty() || ids.back() != id) ids.push_back(id);  // unused lanes repeat the last triangle
        }
      for (uint32_t id : ids) seen.at(id)++;
    } else {
      EXPECT_GT(ref, index) << "depth-first layout: children follow their parent";
      if (ref <= index || ref >= m.bvh.nodes.size()) continue;
      const WideBvhNode& ch = m.bvh.nodes[ref];
      for (int g = 0; g < WideBvhNode::width; ++g) {
        if (ch.bounds[0][g] > ch.bounds[1][g]) continue;
        EXPECT_TRUE(inside(vec3(ch.bounds[0][g], ch.bounds[2][g], ch.bounds[4][g])) &&
                    inside(vec3(ch.bounds[1][g], ch.bounds[3][g], ch.bounds[5][g])))
            << "node " << index << " child " << c << " does not enclose its child's box " << g;
      }
      depth = std::max(depth, check_wide_subtree(m, pos, idx, ref, seen));
    }
  }
  return 1 + depth;
}

// The whole mesh tree: well formed, every triangle in exactly one leaf, and
// no deeper than the traversal stack allows (66 levels, mesh_accel_node_test.h).
void expect_valid_mesh_tree(const MeshAccel& m, std::span<const vec3> pos, std::span<const uint32_t> idx) {
  const size_t n = idx.size() / 3;
  ASSERT_FALSE(m.bvh.nodes.empty());
  ASSERT_EQ(m.triangles.size(), n);
  std::vector<int> seen(n, 0);
  EXPECT_LE(check_wide_subtree(m, pos, idx, 0, seen), 66);
  size_t wrong = 0;
  for (size_t t = 0; t < n; ++t) wrong += seen[t] != 1;
  EXPECT_EQ(wrong, 0u) << "triangles in no leaf or in several";
}

// Rays straight down through the stack at (x, y), and slanted ones through
// its middle, compared with brute force (closest and any hit).
void expect_stack_queries(const SoupMesh& m, const MeshAccel& accel) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-0.2f, 0.2f);
  int hits = 0;
  for (int i = 0; i < 12; ++i) {
    Ray r;
    r.origin = vec3(0.1f + u(rng), 0.1f + u(rng), 2.f);
    r.direction = i % 2 ? vec3(0.f, 0.f, -1.f) : glm::normalize(vec3(u(rng), u(rng), -1.f));
    expect_same_closest(m.positions, m.indices, accel, r, &hits);
    if (::testing::Test::HasFatalFailure()) FAIL() << "ray " << i;
    EXPECT_EQ(occluded_mesh(accel, r), brute_closest(m.positions, m.indices, r).hit) << "ray " << i;
  }
  EXPECT_GE(hits, 10);
}

TEST(Bvh, StacksOfCoincidentTrianglesBuildValidTrees) {
  // Hostile input (issue 12): no plane separates the centroids, so the
  // builder splits by count all the way down. 200k copies of one triangle
  // (shared vertices), then 200k different triangles whose boxes all have
  // the same centre (the origin) but other sizes and shapes.
  constexpr uint32_t n = 200000;
  SoupMesh same;
  same.positions = {vec3(-1.f, -1.f, 0.f), vec3(1.f, -1.f, 0.f), vec3(0.f, 1.f, 0.f)};
  for (uint32_t i = 0; i < n; ++i) same.indices.insert(same.indices.end(), {0u, 1u, 2u});
  MeshAccel a = build_mesh_accel(same.positions, same.indices);
  expect_valid_mesh_tree(a, same.positions, same.indices);
  expect_stack_queries(same, a);

  SoupMesh centred;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> size(0.5f, 2.f), w(-1.f, 1.f);
  for (uint32_t i = 0; i < n; ++i) {
    // Box [-sx, sx] x [-sy, sy] x [-sz, sz], centre exactly 0: the vertices'
    // extremes are negatives of each other.
    const float sx = size(rng), sy = size(rng), sz = 0.2f * size(rng);
    vec3 v[3] = {vec3(-sx, -sy, -sz), vec3(sx, -sy, sz), vec3(w(rng) * sx, sy, 0.f)};
    std::shuffle(v, v + 3, rng);
    for (const vec3& p : v) {
      centred.indices.push_back(uint32_t(centred.positions.size()));
      centred.positions.push_back(p);
    }
  }
  MeshAccel b = build_mesh_accel(centred.positions, centred.indices);
  expect_valid_mesh_tree(b, centred.positions, centred.indices);
  expect_stack_queries(centred, b);
}

TEST(Bvh, FlatTrianglesBeyondTheFloatRangeBuild) {
  // Boxes spanning more than the float range in a plane have an area of
  // inf * 0 = NaN; the builder used to recurse on such a range until the
  // stack overflowed (a 100-face OBJ crashed the renderer).
  SoupMesh m;
  m.positions = {vec3(-3e38f, -3e38f, 0.f), vec3(3e38f, -3e38f, 0.f), vec3(0.f, 3e38f, 0.f),
                 vec3(0.f, 0.f, 1.f),       vec3(1.f, 0.f, 1.f),      vec3(0.f, 1.f, 1.f)};
  for (int i = 0; i < 100; ++i) m.indices.insert(m.indices.end(), {0u, 1u, 2u});
  for (int i = 0; i < 100; ++i) m.indices.insert(m.indices.end(), {3u, 4u, 5u});
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  expect_valid_mesh_tree(accel, m.positions, m.indices);
  int hits = 0;
  for (float x : {0.1f, 0.3f, 2.f, -5.f}) {
    Ray r;
    r.origin = vec3(x, 0.1f, 3.f);
    r.direction = vec3(0.f, 0.f, -1.f);
    expect_same_closest(m.positions, m.indices, accel, r, &hits);
  }
  // The small triangles at z = 1 are hit; the huge ones overflow the
  // triangle test itself (brute force misses them too).
  EXPECT_EQ(hits, 2);
}

TEST(Bvh, TrianglesWithANonFiniteVertexAreLeftOut) {
  // A NaN vertex does not reach the triangle's box (min and max pass over it),
  // so only the vertices themselves tell.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  SoupMesh m;
  m.positions = {vec3(0.f, 0.f, 0.f), vec3(1.f, 0.f, 0.f), vec3(0.f, 1.f, 0.f), vec3(nan, 0.f, 0.f),
                 vec3(0.f, infinity, 0.f)};
  m.indices = {0, 1, 2, 3, 1, 2, 0, 3, 2, 0, 1, 4, 2, 1, 0};
  MeshAccel accel = build_mesh_accel(m.positions, m.indices);
  EXPECT_EQ(accel.triangles, (std::vector<uint32_t>{0, 4}));
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
