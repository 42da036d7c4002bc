// An OBJ read shared among parts beyond its parse (ObjReadOptions::share):
// the smooth normals of large meshes (obj_smooth_normals.h). 2 and 3 parts,
// each a thread of this process exchanging through shared slots, give every
// part the sums and the Scene that one reading alone makes, bit for bit and
// field by field; a part that fails makes every part throw.
#include "importers/obj_test_texts.h"
#include "test_paths.h"
#include "test_work_share.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/obj/obj_smooth_normals.h"
#include "rayform/base/error.h"
#include "rayform/base/work_share.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace rayform {
namespace {

using test::ThreadExchange;

// A wavy grid of n x n positions in `groups` groups of quads and triangles,
// no normals written (so every one is generated), with a degenerate triangle
// (a repeated corner) and a collapsed one (three positions in a point) every
// few cells, and `unused` positions after the grid that no face names.
std::string wavy_grid(int n, int groups, int unused) {
  std::ostringstream s;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      s << "v " << x * 0.1 << " " << y * 0.1 << " " << 0.2 * std::sin(x * 0.7) * std::cos(y * 0.4) << "\n";
  for (int k = 0; k < unused; ++k) s << "v " << k << " 9 9\n";
  s << "v 1 1 1\nv 1 1 1\nv 1 1 1\n";
  const int point = n * n + unused + 1;
  for (int y = 0; y + 1 < n; ++y) {
    if (y % ((n + groups - 1) / groups) == 0) s << "g band" << y << "\n";
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x + 1, b = a + 1, c = a + n, d = c + 1;
      if ((x + y) % 3 == 0) s << "f " << a << " " << b << " " << d << " " << c << "\n";
      else s << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
      if ((x * 7 + y) % 23 == 0) s << "f " << a << " " << b << " " << a << "\n";
      if ((x * 5 + y) % 31 == 0) s << "f " << point << " " << point + 1 << " " << point + 2 << "\n";
    }
  }
  return s.str();
}

// Bit for bit, with the first difference named.
void expect_same_bits(const std::vector<vec3>& a, const std::vector<vec3>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(std::bit_cast<uint32_t>(a[i][k]), std::bit_cast<uint32_t>(b[i][k]))
          << what << ": position " << i << " axis " << k << ": " << a[i][k] << " vs " << b[i][k];
}

// A shape's faces as smooth_normal_sums takes them.
struct ShapeFaces {
  std::vector<size_t> start;
  explicit ShapeFaces(const tinyobj::mesh_t& m) {
    size_t at = 0;
    for (unsigned char n : m.num_face_vertices) {
      start.push_back(at);
      at += n;
    }
  }
};

// Runs body(part, share) on a thread per part; returns the exchanges each made.
template <class Body>
std::vector<int> run_parts(int parts, Body body, int fail_part = -1) {
  ThreadExchange exchange(parts);
  std::vector<WorkShare> shares;
  for (int p = 0; p < parts; ++p) shares.push_back(exchange.share(p, fail_part));
  {
    std::vector<std::jthread> threads;
    for (int p = 0; p < parts; ++p) threads.emplace_back([&, p] { body(p, shares[size_t(p)]); });
  }
  std::vector<int> calls;
  for (int p = 0; p < parts; ++p) calls.push_back(exchange.calls(p));
  return calls;
}

TEST(ObjSharedRead, SmoothNormalSumsAreTheUnsharedOnesOnEveryPart) {
  // Quads and polygons split by LoadObj (polygon_file), a wavy grid with
  // degenerate triangles and unused positions, and a single triangle (fewer
  // positions than parts: some parts sum an empty range).
  for (const std::string& text :
       {test::polygon_file(9), wavy_grid(17, 3, 5), std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")}) {
    const ObjParse parse = test::load_obj_whole(text);
    for (const tinyobj::shape_t& shape : parse.shapes) {
      const ShapeFaces faces(shape.mesh);
      const obj::ObjFaces of{shape.mesh.indices, faces.start, shape.mesh.num_face_vertices};
      const std::vector<vec3> alone = obj::smooth_normal_sums(parse.attrib.vertices, of);
      ASSERT_EQ(alone.size(), parse.attrib.vertices.size() / 3);
      size_t nonzero = 0;
      for (const vec3& n : alone) nonzero += n != vec3(0.f);
      EXPECT_GT(nonzero, 0u) << "the test's sums are not all zero";
      // On one thread (its own loop), alone and shared.
      std::vector<vec3> one_thread;
      tbb::task_arena(1).execute([&] { one_thread = obj::smooth_normal_sums(parse.attrib.vertices, of); });
      expect_same_bits(alone, one_thread, "shape '" + shape.name + "', one thread");
      for (int parts : {2, 3}) {
        for (const int threads : {0, 1}) {  // 0: the default arena
          std::vector<std::vector<vec3>> sums(static_cast<size_t>(parts));
          const std::vector<int> calls = run_parts(parts, [&](int p, const WorkShare& share) {
            auto sum = [&] { sums[size_t(p)] = obj::smooth_normal_sums(parse.attrib.vertices, of, &share); };
            if (threads == 1) tbb::task_arena(1).execute(sum);
            else sum();
          });
          for (int p = 0; p < parts; ++p) {
            const std::string what = "shape '" + shape.name + "', part " + std::to_string(p) + " of " +
                                     std::to_string(parts) + (threads == 1 ? ", one thread" : "");
            EXPECT_EQ(calls[size_t(p)], 1) << what;
            expect_same_bits(alone, sums[size_t(p)], what);
          }
        }
      }
    }
  }
}

TEST(ObjSharedRead, APartThatFailsMakesEveryPartThrow) {
  const ObjParse parse = test::load_obj_whole(wavy_grid(9, 1, 0));
  const tinyobj::mesh_t& mesh = parse.shapes.at(0).mesh;
  const ShapeFaces faces(mesh);
  const obj::ObjFaces of{mesh.indices, faces.start, mesh.num_face_vertices};
  for (int parts : {2, 3}) {
    const int failing = parts - 1;  // sends what a part that threw sends, with no message
    std::vector<std::string> errors(static_cast<size_t>(parts));
    const std::vector<int> calls = run_parts(
        parts,
        [&](int p, const WorkShare& share) {
          try {
            obj::smooth_normal_sums(parse.attrib.vertices, of, &share);
          } catch (const Error& e) {
            errors[size_t(p)] = e.what();
          }
        },
        failing);
    for (int p = 0; p < parts; ++p) {
      EXPECT_EQ(calls[size_t(p)], 1) << "part " << p << " of " << parts;
      EXPECT_EQ(errors[size_t(p)], "generating smooth normals: part " + std::to_string(failing) + " failed")
          << "part " << p << " of " << parts;
    }
  }
}

// Field by field: the meshes (bit for bit), the materials' names, the nodes.
void expect_same_scene(const Scene& a, const Scene& b, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const Mesh &x = a.meshes[i], &y = b.meshes[i];
    const std::string m = "mesh " + std::to_string(i);
    EXPECT_EQ(x.name, y.name) << m;
    EXPECT_EQ(x.source_path, y.source_path) << m;
    expect_same_bits(x.positions, y.positions, m + " positions");
    expect_same_bits(x.normals, y.normals, m + " normals");
    expect_same_bits(x.colors, y.colors, m + " colours");
    EXPECT_TRUE(test::same_bits(x.uvs, y.uvs)) << m << " uvs";
    EXPECT_EQ(x.indices, y.indices) << m;
    EXPECT_EQ(x.face_materials, y.face_materials) << m;
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) EXPECT_EQ(a.materials[i].name, b.materials[i].name);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].name, b.nodes[i].name) << "node " << i;
    EXPECT_EQ(a.nodes[i].children, b.nodes[i].children) << "node " << i;
    EXPECT_EQ(a.nodes[i].shape, b.nodes[i].shape) << "node " << i;
    EXPECT_EQ(a.nodes[i].material, b.nodes[i].material) << "node " << i;
  }
  EXPECT_EQ(a.root, b.root);
}

class ObjSharedReadFile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("obj-shared-read"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::filesystem::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  std::filesystem::path dir_;
};

// read_obj_scene shared among 2 and 3 parts (the parse in chunks, the smooth
// normals of the meshes of at least share_min_faces faces) makes the Scene
// of one read alone, with two exchanges for the parse and one per such mesh.
TEST_F(ObjSharedReadFile, EveryPartReadsTheUnsharedScene) {
  struct Case {
    std::string name, text;
    bool flat;
  };
  const std::vector<Case> cases = {
      {"wavy.obj", wavy_grid(40, 4, 7), false},
      {"grid.obj", test::grid_file(14, true), false},  // normals on some corners: generated on the others
      {"flat.obj", wavy_grid(20, 2, 0), true},         // faceted: no smooth normals, nothing exchanged for them
  };
  for (const Case& c : cases) {
    const std::string path = write(c.name, c.text);
    ObjReadOptions options;
    options.flat = c.flat;
    options.parse_chunk_bytes = 512;
    const Scene alone = read_obj_scene(path, options);
    for (size_t min_faces : {size_t(1), size_t(300)}) {
      size_t sharing = 0;  // meshes of at least min_faces faces
      for (const Mesh& m : alone.meshes) sharing += !c.flat && m.triangle_count() >= min_faces;
      for (int parts : {2, 3}) {
        std::vector<Scene> scenes(static_cast<size_t>(parts));
        std::vector<std::string> errors(static_cast<size_t>(parts));
        const std::vector<int> calls = run_parts(parts, [&](int p, const WorkShare& share) {
          ObjReadOptions o = options;
          o.share = &share;
          o.share_min_faces = min_faces;
          try {
            scenes[size_t(p)] = read_obj_scene(path, o);
          } catch (const Error& e) {
            errors[size_t(p)] = e.what();
          }
        });
        for (int p = 0; p < parts; ++p) {
          const std::string what = c.name + ", part " + std::to_string(p) + " of " + std::to_string(parts) +
                                   ", meshes of " + std::to_string(min_faces) + " faces or more shared";
          ASSERT_EQ(errors[size_t(p)], "") << what;
          EXPECT_EQ(calls[size_t(p)], 2 + int(sharing)) << what;  // the parse's scans and chunks, then the normals
          expect_same_scene(alone, scenes[size_t(p)], what);
        }
      }
    }
  }
}

}  // namespace
}  // namespace rayform
