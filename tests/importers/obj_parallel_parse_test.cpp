// The chunked parallel OBJ parse gives the Scene the whole-file parse gives:
// generated files with every kind of line cut into chunks of many sizes (so
// that state lines land on chunk ends), what must fall back to the
// whole-file parse, and every OBJ file of the shared assets.
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/obj/text_stream_buffer.h"
#include "rayform/base/error.h"
#include "importers/obj_test_texts.h"
#include "test_importers.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;
using test::grid_attributes;
using test::grid_file;
using test::mtl_text;
using test::NoMaterials;
using test::polygon_file;
using test::same_bits;

void expect_same_scene(const Scene& a, const Scene& b, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const Mesh &x = a.meshes[i], &y = b.meshes[i];
    EXPECT_EQ(x.name, y.name) << "mesh " << i;
    EXPECT_TRUE(same_bits(x.positions, y.positions)) << "mesh " << i;
    EXPECT_TRUE(same_bits(x.normals, y.normals)) << "mesh " << i;
    EXPECT_TRUE(same_bits(x.uvs, y.uvs)) << "mesh " << i;
    EXPECT_TRUE(same_bits(x.colors, y.colors)) << "mesh " << i;
    EXPECT_EQ(x.indices, y.indices) << "mesh " << i;
    EXPECT_EQ(x.face_materials, y.face_materials) << "mesh " << i;
  }
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const Node &x = a.nodes[i], &y = b.nodes[i];
    EXPECT_EQ(x.name, y.name) << "node " << i;
    EXPECT_EQ(x.kind, y.kind) << "node " << i;
    EXPECT_EQ(x.children, y.children) << "node " << i;
    EXPECT_EQ(x.shape, y.shape) << "node " << i;
    EXPECT_EQ(x.material, y.material) << "node " << i;
  }
  EXPECT_EQ(a.root, b.root);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].diffuse, b.materials[i].diffuse);
    EXPECT_EQ(a.materials[i].diffuse_texture, b.materials[i].diffuse_texture);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) EXPECT_EQ(a.textures[i].path, b.textures[i].path);
}

struct Read {
  Scene scene;
  std::vector<std::string> warnings;
  std::string error;
};

Read read(const fs::path& file, size_t chunk_bytes, bool flat = false) {
  Read r;
  ObjReadOptions o;
  o.parse_chunk_bytes = chunk_bytes;
  o.flat = flat;
  try {
    r.scene = read_obj_scene(file.string(), o, &r.warnings);
  } catch (const Error& e) {
    r.error = e.what();
  }
  return r;
}

// The file read whole and in chunks of many sizes: the same scene, warnings and errors.
void expect_chunked_same(const fs::path& file, bool flat = false) {
  const Read whole = read(file, ObjReadOptions::serial, flat);
  for (size_t chunk : {1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, 377, 610, 987, 1 << 20}) {
    const std::string what = file.filename().string() + " in chunks of " + std::to_string(chunk);
    const Read part = read(file, chunk, flat);
    EXPECT_EQ(whole.error, part.error) << what;
    EXPECT_EQ(whole.warnings, part.warnings) << what;
    expect_same_scene(whole.scene, part.scene, what);
  }
}

bool chunked(const std::string& text, size_t chunk_bytes) {
  ObjParse out;
  return parse_obj_chunked(
      text, [] { return std::make_unique<NoMaterials>(); }, chunk_bytes, &out);
}

class ObjParallelParse : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::temp_dir("obj-parallel");
    std::ofstream(dir_ / "m.mtl", std::ios::binary) << mtl_text;
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  fs::path dir_;
};

TEST_F(ObjParallelParse, StateLinesOnEveryChunkEnd) {
  const std::string text = grid_file(6, true);
  EXPECT_TRUE(chunked(text, 1));
  EXPECT_TRUE(chunked(text, 100));
  expect_chunked_same(write("grid.obj", text));
  expect_chunked_same(write("grid-flat.obj", text), /*flat*/ true);
}

TEST_F(ObjParallelParse, PositionsOnlyAndVertexColours) {
  std::string text = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 1 1 0 0.5 0.5 0.5\nf 1 2 3\nf 2 4 3\n";
  EXPECT_TRUE(chunked(text, 1));
  expect_chunked_same(write("colours.obj", text));
  // Colours on some vertices only: none at all.
  expect_chunked_same(write("some-colours.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n"));
}

TEST_F(ObjParallelParse, LineEndsCommentsAndBackslashes) {
  std::string text = grid_file(4, true);
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_TRUE(chunked(crlf, 7));
  expect_chunked_same(write("crlf.obj", crlf));
  // No line end after the last face.
  expect_chunked_same(write("no-last-newline.obj", text.substr(0, text.size() - 1)));
  // tinyobjloader does not join lines ending in '\': a face cut so is two lines.
  expect_chunked_same(write("backslash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 \\\n3\nf 2 4 3 # c\n"));
  expect_chunked_same(
      write("usemtl-before-mtllib.obj", "usemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib m.mtl\nf 1 2 3\nf 1 2 3\n"));
}

TEST_F(ObjParallelParse, WhatFallsBackStillGivesTheSame) {
  const std::string head = "mtllib m.mtl\n" + grid_attributes(3);
  struct Case {
    const char* name;
    std::string faces;
  };
  const Case cases[] = {
      {"quad-names-later-vertex", "usemtl red\nf 1 2 5 10\nv 9 9 9\nusemtl green\nf 1 2 3\n"},
      {"quad-names-vertex-after-group-end", "usemtl red\nf 1 2 5 10\nusemtl green\nv 9 9 9\nf 1 2 3\n"},
      {"ngon-names-later-vertex", "g poly\nf 1 2 3 6 9 8 10\nv 9 9 9\n"},
      {"negative", "f -9 -8 -6\nf 1 2 3\nf -1 -2 -3\n"},
      {"lines", "f 1 2 5\nl 1 2 3\np 4\nf 2 3 6\n"},
      {"degenerate", "f 1 2\nf 1 2 5\n"},
      {"empty-group", "f 1 2 5\ng \nf 2 3 6\n"},
      {"bare-g", "f 1 2 5\ng\nf 2 3 6\n"},  // "g" alone is no group line to tinyobjloader
      {"lone-cr", "f 1 2 5\rf 2 3 6\n"},
      {"tag", "t crease 2/1/0 1 2 0.5\nf 1 2 5\n"},
      {"out-of-range", "f 1 2 5\nf 1 2 99\n"},
      {"zero-index", "f 1 2 5\nf 0 1 2\n"},
      {"huge-index", "f 1 2 5\nf 1 2 3000000000\n"},
      {"bad-uv-index", "f 1/1 2/2 5/40\nf 1/1 2/2 5/5\n"},
  };
  for (const Case& c : cases) {
    const std::string text = head + c.faces;
    const bool expect_chunked = std::string(c.name) == "bad-uv-index" || std::string(c.name) == "bare-g";
    SCOPED_TRACE(c.name);
    EXPECT_EQ(chunked(text, 16), expect_chunked) << c.name;
    expect_chunked_same(write(std::string(c.name) + ".obj", text));
  }
}

TEST_F(ObjParallelParse, PolygonsAreSplitAsLoadObjSplitsThem) {
  const std::string text = polygon_file(9);
  EXPECT_TRUE(chunked(text, 1));
  EXPECT_TRUE(chunked(text, 300));
  expect_chunked_same(write("polygons.obj", text));
  expect_chunked_same(write("polygons-flat.obj", text), /*flat*/ true);
  // The split itself, not only the scene it makes (vertices shared by
  // position could hide a different diagonal in the indices alone).
  const ObjParse whole = test::load_obj_whole(text);
  ObjParse part;
  ASSERT_TRUE(parse_obj_chunked(
      text, [] { return std::make_unique<test::NoMaterials>(); }, 97, &part));
  test::expect_same_shapes(whole, part, "chunks of 97");
  size_t triangles = 0;
  for (const tinyobj::shape_t& shape : whole.shapes) triangles += shape.mesh.num_face_vertices.size();
  EXPECT_GT(triangles, 300u);
  // A face of 256 corners (more than LoadObj's count of corners holds) falls back.
  std::string big = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (int k = 0; k < 256; ++k) big.append(" ").append(std::to_string(1 + k % 3));
  EXPECT_FALSE(chunked(big + "\n", 8));
}

// One g/o section of triangles (a name, a material and a smoothing group
// set at the top, a material switch half-way): the chunks write the faces
// straight into the one shape's arrays, plain ones as they parse, the
// others after; the same shapes as LoadObj, bit for bit.
TEST_F(ObjParallelParse, OneSectionOfTrianglesIsJoinedInPlace) {
  const int n = 12;
  std::string text = "mtllib m.mtl\no the name\nusemtl red\ns 2\n" + grid_attributes(n);
  for (int y = 0; y + 1 < n; ++y) {
    if (y == n / 2) text += "usemtl green\n";
    for (int x = 0; x + 1 < n; ++x) text += test::cell(n, x, y, x + 2 * y);
  }
  const ObjParse whole = test::load_obj_whole(text);
  ASSERT_EQ(whole.shapes.size(), 1u);
  EXPECT_EQ(whole.shapes[0].name, "the name");
  for (size_t chunk : {size_t(50), size_t(333), size_t(4000)}) {
    ObjParse part;
    ASSERT_TRUE(parse_obj_chunked(
        text, [] { return std::make_unique<test::NoMaterials>(); }, chunk, &part))
        << chunk;
    test::expect_same_shapes(whole, part, "chunks of " + std::to_string(chunk));
    test::expect_same_vertices(whole, part, "chunks of " + std::to_string(chunk));
  }
  expect_chunked_same(write("one-section.obj", text));
  // Faces before the first g/o line and after it are two sections: joined as before.
  expect_chunked_same(write("two-sections.obj", grid_attributes(3) + "f 1 2 5\ng a\nf 2 3 6\n"));
}

TEST_F(ObjParallelParse, SharedAssets) {
  RAYFORM_REQUIRE_SHARED();
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(test::shared_dir() / "assets")) {
    std::string ext = e.path().extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (!e.is_regular_file() || ext != ".obj") continue;
    const Read whole = read(e.path(), ObjReadOptions::serial);
    for (size_t chunk : {size_t(64), size_t(4096), size_t(1) << 18}) {
      const Read part = read(e.path(), chunk);
      const std::string what = e.path().string() + " in chunks of " + std::to_string(chunk);
      EXPECT_EQ(whole.error, part.error) << what;
      EXPECT_EQ(whole.warnings, part.warnings) << what;
      expect_same_scene(whole.scene, part.scene, what);
    }
    ++files;
  }
  EXPECT_GT(files, 40u);
  // The large triangle meshes do take the chunked path.
  for (const char* name : {"obj/stanford-bunny.obj", "obj/spot.obj", "obj/teapot.obj", "obj/beast.obj"}) {
    std::ifstream in(test::asset(name), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_TRUE(chunked(text.str(), 1 << 16)) << name;
  }
}

}  // namespace
}  // namespace rayform
