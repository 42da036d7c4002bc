// The shared build of a mesh BVH (build_mesh_accel with a WorkShare,
// src/accel/mesh_accel.h): parts run as threads of this process with an
// in-process exchange (a barrier and a slot per part) each end with exactly
// the MeshAccel of the unshared build, byte for byte, for 2, 3 and 5 parts,
// on meshes of every kind: large and bumpy, closed, flat, with NaN vertices,
// coincident, tiny, empty, and ones under the threshold (no exchange).
#include "rayform/accel/mesh_accel.h"
#include "rayform/scene/procedural_mesh.h"
#include "test_bytes.h"
#include "test_work_share.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace rayform {
namespace {

using test::same_bytes;

using test::ThreadExchange;

void expect_same(const MeshAccel& want, const MeshAccel& got, const std::string& what) {
  EXPECT_EQ(want.bvh.nodes.size(), got.bvh.nodes.size()) << what;
  EXPECT_TRUE(same_bytes(want.bvh.nodes, got.bvh.nodes)) << what << ": nodes differ";
  EXPECT_TRUE(same_bytes(want.packets, got.packets)) << what << ": packets differ";
  EXPECT_EQ(want.triangles, got.triangles) << what << ": leaf order differs";
  EXPECT_EQ(std::memcmp(&want.bvh.root_bounds, &got.bvh.root_bounds, sizeof(Bounds3)), 0) << what << ": root bounds";
}

struct Shared {
  std::vector<MeshAccel> accels;
  ThreadExchange* exchange = nullptr;
  std::vector<std::exception_ptr> errors;
};

// Builds `mesh` in `parts` threads sharing one exchange.
void build_in_parts(const Mesh& mesh, const BvhBuildOptions& o, int parts, ThreadExchange& ex, Shared& out,
                    int fail_part = -1) {
  out.accels.assign(parts, MeshAccel{});
  out.errors.assign(parts, nullptr);
  out.exchange = &ex;
  std::vector<std::thread> threads;
  for (int p = 0; p < parts; ++p)
    threads.emplace_back([&, p] {
      const WorkShare share = ex.share(p, fail_part);
      try {
        out.accels[p] = build_mesh_accel(mesh.positions, mesh.indices, o, &share);
      } catch (...) {
        out.errors[p] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
}

struct Case {
  std::string name;
  Mesh mesh;
  BvhBuildOptions options;
  bool shared;  // at least options.share_min_triangles triangles
};

std::vector<Case> cases() {
  std::vector<Case> c;
  BvhBuildOptions low;
  low.share_min_triangles = 1;
  // Over the default threshold.
  c.push_back({"torus 80k", make_bumpy_torus(80000, 3), {}, true});
  c.push_back({"torus 30k", make_bumpy_torus(30000, 7), low, true});
  c.push_back({"icosphere 20k", make_icosphere(5), low, true});
  BvhBuildOptions other = low;
  other.max_leaf_size = 1;
  other.bins = 2;
  c.push_back({"icosphere leaf 1 bins 2", make_icosphere(4), other, true});
  other.max_leaf_size = 16;
  other.bins = 32;
  other.traversal_cost = 4.f;
  c.push_back({"torus leaf 16 bins 32", make_bumpy_torus(20000, 5), other, true});
  c.push_back({"flat grid", make_grid(120, 90), low, true});
  Mesh nan = make_bumpy_torus(20000, 2);
  for (size_t i = 0; i < nan.positions.size(); i += 97) nan.positions[i].y = std::numeric_limits<float>::quiet_NaN();
  c.push_back({"NaN vertices", nan, low, true});
  Mesh same;  // every triangle on one spot: no SAH split, splits by count
  same.positions = {vec3(1.f, 2.f, 3.f), vec3(1.f, 2.f, 3.f), vec3(1.f, 2.f, 3.f)};
  for (int t = 0; t < 5000; ++t) same.indices.insert(same.indices.end(), {0u, 1u, 2u});
  c.push_back({"coincident", same, low, true});
  c.push_back({"cube (a single leaf)", make_cube(), low, true});
  c.push_back({"empty", Mesh{}, BvhBuildOptions{4, 16, 1.f, 0}, true});
  Mesh all_nan = make_cube();
  for (vec3& v : all_nan.positions) v.x = std::numeric_limits<float>::quiet_NaN();
  c.push_back({"all NaN", all_nan, low, true});
  BvhBuildOptions high;
  high.share_min_triangles = 1000;
  c.push_back({"under the threshold", make_icosphere(2), high, false});
  c.push_back({"under the default threshold", make_bumpy_torus(20000, 4), {}, false});
  return c;
}

TEST(MeshAccelShare, EveryPartBuildsTheUnsharedStructure) {
  for (const Case& c : cases()) {
    const MeshAccel whole = build_mesh_accel(c.mesh.positions, c.mesh.indices, c.options);
    for (int parts : {2, 3, 5}) {
      const std::string what = c.name + ", " + std::to_string(parts) + " parts";
      ThreadExchange ex(parts);
      Shared s;
      build_in_parts(c.mesh, c.options, parts, ex, s);
      for (int p = 0; p < parts; ++p) {
        ASSERT_FALSE(s.errors[p]) << what << ": part " << p << " threw";
        expect_same(whole, s.accels[p], what + ", part " + std::to_string(p));
        EXPECT_EQ(ex.calls(p), c.shared ? 1 : 0) << what << ": exchanges made by part " << p;
      }
    }
  }
}

TEST(MeshAccelShare, LargeMeshesSpreadTheSubtreesOverEveryPart) {
  // Every part sends subtrees (more than the one flag byte), and none sends
  // more than twice its even share of the structure.
  const Mesh torus = make_bumpy_torus(80000, 3);
  const MeshAccel whole = build_mesh_accel(torus.positions, torus.indices);
  // What travels: nodes, packets as their four triangle ids, triangles.
  const size_t structure = whole.bvh.nodes.size() * sizeof(WideBvhNode) + whole.packets.size() * 4 * sizeof(uint32_t) +
                           whole.triangles.size() * sizeof(uint32_t);
  for (int parts : {2, 3, 5}) {
    ThreadExchange ex(parts);
    Shared s;
    build_in_parts(torus, {}, parts, ex, s);
    size_t sent = 0;
    for (int p = 0; p < parts; ++p) {
      ASSERT_FALSE(s.errors[p]);
      EXPECT_GT(ex.sent(p), 1000u) << parts << " parts: part " << p << " built nothing";
      EXPECT_LT(ex.sent(p), 2 * structure / parts) << parts << " parts: part " << p << " built too much";
      sent += ex.sent(p);
    }
    // The subtrees sent are the structure less the top the parts all make
    // (with headers and alignment padding): each is sent once.
    EXPECT_LT(sent, structure + structure / 100);
    EXPECT_GT(sent, structure * 9 / 10);
  }
}

TEST(MeshAccelShare, APartThatFailsMakesEveryPartThrow) {
  const Mesh torus = make_bumpy_torus(20000, 6);
  BvhBuildOptions o;
  o.share_min_triangles = 1;
  ThreadExchange ex(3);
  Shared s;
  build_in_parts(torus, o, 3, ex, s, 1);
  for (int p = 0; p < 3; ++p) {
    ASSERT_TRUE(s.errors[p]) << "part " << p << " went on after part 1 failed";
    try {
      std::rethrow_exception(s.errors[p]);
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("part 1 of a shared build failed"), std::string::npos) << e.what();
    }
    EXPECT_EQ(ex.calls(p), 1);
  }
}

}  // namespace
}  // namespace rayform
