// The chunked parallel OBJ parse gives the Scene the whole-file parse gives:
// generated files with every kind of line cut into chunks of many sizes (so
// that state lines land on chunk ends), what must fall back to the
// whole-file parse, and every OBJ file of the shared assets.
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/obj/text_stream_buffer.h"
#include "rayform/scene/error.h"
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

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

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

class NoMaterials : public tinyobj::MaterialReader {
 public:
  bool operator()(const std::string&, std::vector<tinyobj::material_t>*, std::map<std::string, int>*, std::string*,
                  std::string*) override {
    return true;
  }
};

bool chunked(const std::string& text, size_t chunk_bytes) {
  ObjParse out;
  return parse_obj_chunked(
      text, [] { return std::make_unique<NoMaterials>(); }, chunk_bytes, &out);
}

const char* mtl_text =
    "newmtl red\nKd 1 0 0\n\n"
    "newmtl green\nKd 0 1 0\n\n"
    "newmtl blue\nKd 0 0 1\nNs 10\nKs 0.5 0.5 0.5\n";

// A grid of n x n vertices with uvs and normals (one of them of zero length).
std::string grid_attributes(int n) {
  std::ostringstream s;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) s << "v " << x * 0.25 << " " << y * 0.5 << " " << (x * y) % 3 * 0.1 << "\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) s << "vt " << x / double(n) << " " << y / double(n) << "\n";
  s << "vn 0 0 1\nvn 0 1 0\nvn 0 0 0\nvn 1 0 0\n";
  return s.str();
}

// Triangles of the grid's cell (x, y), corners written in one of several styles.
std::string cell(int n, int x, int y, int style) {
  const int a = y * n + x + 1, b = a + 1, c = a + n, d = c + 1;
  auto corner = [&](int v, int k) {
    switch ((style + k) % 4) {
      case 0: return std::to_string(v);
      case 1: return std::to_string(v) + "/" + std::to_string(v);
      case 2: return std::to_string(v) + "//" + std::to_string(1 + (v + k) % 4);
      default: return std::to_string(v) + "/" + std::to_string(v) + "/" + std::to_string(1 + v % 4);
    }
  };
  return "f " + corner(a, 0) + " " + corner(b, 1) + " " + corner(d, 2) + "\nf  " + corner(a, 3) + "\t" + corner(d, 4) +
         " " + corner(c, 5) + " \n";
}

// Faces over the grid with o/g/usemtl/s switches, comments and empty lines between them.
std::string grid_file(int n, bool mixed_styles) {
  std::ostringstream s;
  s << "# generated\n\nmtllib m.mtl\n" << grid_attributes(n);
  const char* state[] = {"o first",    "usemtl red",   "s 1",   "g a b", "usemtl unknown", "",
                         "# comment",  "usemtl green", "s off", "o",     "usemtl blue",    "g  spaced  ",
                         "usemtl red", "o last one "};
  int i = 0;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x, ++i) {
      if (i % 3 == 0) s << state[(i / 3) % std::size(state)] << "\n";
      s << cell(n, x, y, mixed_styles ? i : 0);
    }
  return s.str();
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

// Quads whose diagonals differ both ways and tie, polygons of 5 to 255
// corners (convex, concave, a star, with corners in a line, all in a line,
// repeated corners, in planes facing x, y and z), in every corner style.
std::string polygon_file(int n) {
  std::ostringstream s;
  s << "mtllib m.mtl\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      s << "v " << x * 0.25 + ((x * 7 + y * 3) % 5) * 0.03 << " " << y * 0.5 + ((x + y * 5) % 3) * 0.05 << " "
        << (x * y) % 3 * 0.1 << "\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) s << "vt " << x / double(n) << " " << y / double(n) << "\n";
  s << "vn 0 0 1\nvn 0 1 0\nvn 0 0 0\nvn 1 0 0\n";
  const int grid = n * n;
  // Shapes of their own: an arrow (concave at its 4th corner), a five-pointed
  // star, a hexagon with corners in a line, five corners in one line, a
  // square (equal diagonals), a 40-gon and a 255-gon (circles) facing x.
  const std::vector<std::array<double, 3>> own = {
      {0, 0, 0},    {4, 0, 0},       {4, 4, 0},       {2, 1, 0},      {0, 4, 0},                  // arrow
      {0, 3, 1},    {0.7, 1, 1},     {2.9, 1, 1},     {1.1, -0.3, 1}, {1.8, -2.4, 1},             // star
      {0, -0.9, 1}, {-1.8, -2.4, 1}, {-1.1, -0.3, 1}, {-2.9, 1, 1},   {-0.7, 1, 1},               //
      {0, 0, 2},    {1, 0, 2},       {2, 0, 2},       {2, 1, 2},      {1, 1, 2},      {0, 1, 2},  // hexagon
      {0, 0, 3},    {1, 0, 3},       {2, 0, 3},       {3, 0, 3},      {4, 0, 3},                  // a line
      {0, 0, 4},    {1, 0, 4},       {1, 1, 4},       {0, 1, 4}};                                 // square
  for (const auto& p : own) s << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  const int circle40 = grid + int(own.size()) + 1, circle255 = circle40 + 40;
  for (int k = 0; k < 40; ++k) s << "v 5 " << std::cos(k * 0.15707963) << " " << std::sin(k * 0.15707963) << "\n";
  for (int k = 0; k < 255; ++k) s << "v 6 " << std::cos(k * 0.02463994) << " " << std::sin(k * 0.02463994) << "\n";
  auto corner = [&](int v, int k) {
    const int t = (v - 1) % grid + 1;
    switch (k % 4) {
      case 0: return std::to_string(v);
      case 1: return std::to_string(v) + "/" + std::to_string(t);
      case 2: return std::to_string(v) + "//" + std::to_string(1 + (v + k) % 4);
      default: return std::to_string(v) + "/" + std::to_string(t) + "/" + std::to_string(1 + v % 4);
    }
  };
  auto face = [&](std::initializer_list<int> vs, int style) {
    s << "f";
    int k = style;
    for (int v : vs) s << " " << corner(v, k++);
    s << "\n";
  };
  const char* state[] = {"o first", "usemtl red", "s 1", "g a b", "usemtl green", "s off", "o", "usemtl blue"};
  int i = 0;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x, ++i) {
      if (i % 4 == 0) s << state[(i / 4) % std::size(state)] << "\n";
      const int a = y * n + x + 1, b = a + 1, c = a + n, d = c + 1;
      if (i % 7 == 3 && x + 2 < n) face({a, b, b + 1, d + 1, d, c}, i);  // two cells: corners in a line
      else if (i % 7 == 5 && x + 2 < n) face({a, b + 1, d + 1, c}, i);   // two cells, a long quad
      else if (i % 11 == 6 && x + 2 < n) face({a, b, b + 1, d + 1, c}, i);
      else face({a, b, d, c}, i);
      if (i % 13 == 0) {
        const int o = grid + 1;
        face({o, o + 1, o + 2, o + 3, o + 4}, i);
        face({o + 5, o + 6, o + 7, o + 8, o + 9, o + 10, o + 11, o + 12, o + 13, o + 14}, i);
        face({o + 15, o + 16, o + 17, o + 18, o + 19, o + 20}, i);
        face({o + 21, o + 22, o + 23, o + 24, o + 25}, i);
        face({o + 26, o + 27, o + 28, o + 29}, i);
        face({o + 26, o + 27, o + 27, o + 28, o + 29}, i);  // a repeated corner
      }
    }
  s << "f";
  for (int k = 0; k < 40; ++k) s << " " << circle40 + k;
  s << "\nf";
  for (int k = 0; k < 255; ++k) s << " " << circle255 + k;
  s << "\n";
  return s.str();
}

TEST_F(ObjParallelParse, PolygonsAreSplitAsLoadObjSplitsThem) {
  const std::string text = polygon_file(9);
  EXPECT_TRUE(chunked(text, 1));
  EXPECT_TRUE(chunked(text, 300));
  expect_chunked_same(write("polygons.obj", text));
  expect_chunked_same(write("polygons-flat.obj", text), /*flat*/ true);
  // The split itself, not only the scene it makes (vertices shared by
  // position could hide a different diagonal in the indices alone).
  ObjParse whole, part;
  {
    TextStreamBuffer buffer(text);
    std::istream in(&buffer);
    NoMaterials none;
    std::vector<tinyobj::material_t> materials;
    std::string err;
    ASSERT_TRUE(tinyobj::LoadObj(&whole.attrib, &whole.shapes, &materials, &whole.warn, &err, &in, &none, true, false));
  }
  ASSERT_TRUE(parse_obj_chunked(
      text, [] { return std::make_unique<NoMaterials>(); }, 97, &part));
  ASSERT_EQ(whole.shapes.size(), part.shapes.size());
  size_t triangles = 0;
  for (size_t i = 0; i < whole.shapes.size(); ++i) {
    const tinyobj::mesh_t &a = whole.shapes[i].mesh, &b = part.shapes[i].mesh;
    ASSERT_EQ(a.indices.size(), b.indices.size()) << "shape " << i;
    for (size_t k = 0; k < a.indices.size(); ++k) {
      EXPECT_EQ(a.indices[k].vertex_index, b.indices[k].vertex_index) << "shape " << i << " corner " << k;
      EXPECT_EQ(a.indices[k].texcoord_index, b.indices[k].texcoord_index) << "shape " << i << " corner " << k;
      EXPECT_EQ(a.indices[k].normal_index, b.indices[k].normal_index) << "shape " << i << " corner " << k;
    }
    EXPECT_EQ(a.num_face_vertices, b.num_face_vertices) << "shape " << i;
    EXPECT_EQ(a.material_ids, b.material_ids) << "shape " << i;
    EXPECT_EQ(a.smoothing_group_ids, b.smoothing_group_ids) << "shape " << i;
    triangles += a.num_face_vertices.size();
  }
  EXPECT_GT(triangles, 300u);
  // A face of 256 corners (more than LoadObj's count of corners holds) falls back.
  std::string big = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (int k = 0; k < 256; ++k) big.append(" ").append(std::to_string(1 + k % 3));
  EXPECT_FALSE(chunked(big + "\n", 8));
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
