// OBJ texts made for the tests of the chunked parse (obj_parallel_parse.h),
// alone and shared among parts, and how their parses are compared.
#pragma once

#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/text_stream_buffer.h"

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <array>
#include <cmath>
#include <cstring>
#include <istream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace rayform::test {

class NoMaterials : public tinyobj::MaterialReader {
 public:
  bool operator()(const std::string&, std::vector<tinyobj::material_t>*, std::map<std::string, int>*, std::string*,
                  std::string*) override {
    return true;
  }
};

inline const char* mtl_text =
    "newmtl red\nKd 1 0 0\n\n"
    "newmtl green\nKd 0 1 0\n\n"
    "newmtl blue\nKd 0 0 1\nNs 10\nKs 0.5 0.5 0.5\n";

// A grid of n x n vertices with uvs and normals (one of them of zero length).
inline std::string grid_attributes(int n) {
  std::ostringstream s;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) s << "v " << x * 0.25 << " " << y * 0.5 << " " << (x * y) % 3 * 0.1 << "\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) s << "vt " << x / double(n) << " " << y / double(n) << "\n";
  s << "vn 0 0 1\nvn 0 1 0\nvn 0 0 0\nvn 1 0 0\n";
  return s.str();
}

// Triangles of the grid's cell (x, y), corners written in one of several styles.
inline std::string cell(int n, int x, int y, int style) {
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
inline std::string grid_file(int n, bool mixed_styles) {
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

// Quads whose diagonals differ both ways and tie, polygons of 5 to 255
// corners (convex, concave, a star, with corners in a line, all in a line,
// repeated corners, in planes facing x, y and z), in every corner style.
inline std::string polygon_file(int n) {
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

// One tinyobj::LoadObj over the whole text (triangulated, as the reader asks).
inline ObjParse load_obj_whole(const std::string& text) {
  ObjParse whole;
  TextStreamBuffer buffer(text);
  std::istream in(&buffer);
  NoMaterials none;
  std::vector<tinyobj::material_t> materials;
  std::string err;
  EXPECT_TRUE(tinyobj::LoadObj(&whole.attrib, &whole.shapes, &materials, &whole.warn, &err, &in, &none, true, false))
      << err;
  return whole;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The shapes, field by field: names, every corner's three indices, corner
// counts, materials and smoothing groups.
inline void expect_same_shapes(const ObjParse& a, const ObjParse& b, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  for (size_t i = 0; i < a.shapes.size(); ++i) {
    EXPECT_EQ(a.shapes[i].name, b.shapes[i].name) << "shape " << i;
    const tinyobj::mesh_t &x = a.shapes[i].mesh, &y = b.shapes[i].mesh;
    ASSERT_EQ(x.indices.size(), y.indices.size()) << "shape " << i;
    for (size_t k = 0; k < x.indices.size(); ++k) {
      EXPECT_EQ(x.indices[k].vertex_index, y.indices[k].vertex_index) << "shape " << i << " corner " << k;
      EXPECT_EQ(x.indices[k].texcoord_index, y.indices[k].texcoord_index) << "shape " << i << " corner " << k;
      EXPECT_EQ(x.indices[k].normal_index, y.indices[k].normal_index) << "shape " << i << " corner " << k;
    }
    EXPECT_EQ(x.num_face_vertices, y.num_face_vertices) << "shape " << i;
    EXPECT_EQ(x.material_ids, y.material_ids) << "shape " << i;
    EXPECT_EQ(x.smoothing_group_ids, y.smoothing_group_ids) << "shape " << i;
  }
}

// The vertex arrays the reader uses (positions, normals, uvs, colours), bit for bit.
inline void expect_same_vertices(const ObjParse& a, const ObjParse& b, const std::string& what) {
  EXPECT_TRUE(same_bits(a.attrib.vertices, b.attrib.vertices)) << what;
  EXPECT_TRUE(same_bits(a.attrib.normals, b.attrib.normals)) << what;
  EXPECT_TRUE(same_bits(a.attrib.texcoords, b.attrib.texcoords)) << what;
  EXPECT_TRUE(same_bits(a.attrib.colors, b.attrib.colors)) << what;
}

}  // namespace rayform::test
