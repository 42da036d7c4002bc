// The chunked parallel OBJ parse gives the Scene the whole-file parse gives:
// generated files with every kind of line cut into chunks of many sizes (so
// that state lines land on chunk ends), what must fall back to the
// whole-file parse, and every OBJ file of the shared assets.
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/scene/error.h"
#include "test_importers.h"
#include "test_paths.h"

#include <gtest/gtest.h>

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
      {"quads", "usemtl red\nf 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\n"},
      {"ngon", "g poly\nf 1 2 3 6 9 8 7 4\n"},
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
    EXPECT_EQ(chunked(text, 16), expect_chunked) << c.name;
    expect_chunked_same(write(std::string(c.name) + ".obj", text));
  }
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
  for (const char* name : {"obj/stanford-bunny.obj", "obj/spot.obj", "obj/teapot.obj"}) {
    std::ifstream in(test::asset(name), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_TRUE(chunked(text.str(), 1 << 16)) << name;
  }
}

}  // namespace
}  // namespace rayform
