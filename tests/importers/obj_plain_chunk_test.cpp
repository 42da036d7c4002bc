// The plain chunks of the chunked OBJ parse (obj_plain_chunk.h): which
// chunks the scan calls plain (and whose faces it lets the parse read
// itself), and that the parse of one gives, array for array and bit for
// bit, what tinyobj::LoadObj gives for it.
#include "rayform/importers/obj/obj_plain_chunk.h"
#include "rayform/importers/obj/obj_chunk_scan.h"
#include "rayform/importers/obj/text_stream_buffer.h"
#include "importers/obj_test_texts.h"

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <istream>
#include <string>

namespace rayform::obj {
namespace {

using test::same_bits;

bool plain(const std::string& text) {
  const ChunkScan s = scan_chunk(text, 0, text.size());
  return s.supported && s.plain;
}

TEST(ObjPlainChunk, TheScanCallsPlainOnlyWhatTheCallbacksReadAsLoadObjDoes) {
  // Plain: vertex lines, faces of plain corners in every style, comments,
  // blank and unknown lines, tabs, line ends in "\r\n".
  for (const char* text : {
           "v 1 2 3\nvn 0 0 1\nvt 0.5 0.5\nf 1/1/1 2/2/1 3/3/1\n",
           "f 1 2 3\nf 1//1\t2//1 3//1\nf 1/1 2/2 3/3 4/4\n",
           "# comment\n\nfoo bar\nvp 1 2\nf 123456789 2 3\n",
           "v 1 2 3 1\nv 1 2 3 1 0 0\nf 1 2 3\r\n",  // a colour after the first `v` line: LoadObj keeps none
           "vt 0.5 0.5 0.25\nf 9 10 11",
       })
    EXPECT_TRUE(plain(text)) << text;
  // Not plain: corners naming a uv or normal whose raw triple may not be
  // LoadObj's index + 1 (zero, a missing number, a sign, a leading zero,
  // other characters), state lines, and a colour on the first `v` line.
  // (Corners of a position alone read alike in both parsers but where they
  // read 0: the callback parse refuses those itself, below.)
  for (const char* text : {
           "f 1/0/1 2/1/1 3/1/1\n",
           "f 01/1 2/1 3/1\n",
           "f 1/ 2 3\n",
           "f 1// 2 3\n",
           "f 1/2/ 2 3\n",
           "f +1//1 2//1 3//1\n",
           "f 1x/1 2/1 3/1\n",
           "f 1/1/1/1 2 3\n",
           "f 1/1\v2/2 3/3 4/4\n",
           "usemtl red\nf 1 2 3\n",
           "usemtlred\n",
           "mtllib m.mtl\n",
           "g a\nf 1 2 3\n",
           "o a\n",
           "s 1\n",
           "v 1 2 3 1 0 0\nv 1 2 3\n",
       })
    EXPECT_FALSE(plain(text)) << text;
}

// LoadObj over `prefix` + `body` (polygons whole), as the chunked parse calls it.
ChunkParse load_obj(const std::string& prefix, const std::string& body) {
  ChunkParse r;
  TextStreamBuffer buffer(prefix, body);
  std::istream in(&buffer);
  test::NoMaterials none;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  r.ok = tinyobj::LoadObj(&r.attrib, &r.shapes, &materials, &warn, &err, &in, &none, /*triangulate*/ false,
                          /*default_vcols_fallback*/ false);
  return r;
}

void expect_same(const ChunkParse& a, const ChunkParse& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_TRUE(a.ok);
  EXPECT_TRUE(b.ok);
  ObjParse x, y;
  x.attrib = a.attrib;
  x.shapes = a.shapes;
  y.attrib = b.attrib;
  y.shapes = b.shapes;
  test::expect_same_shapes(x, y, what);
  test::expect_same_vertices(x, y, what);
}

TEST(ObjPlainChunk, TheCallbackParseGivesWhatLoadObjGives) {
  // Every corner style of the grid's cells, polygons, uvs with a w,
  // numbers in every form tinyobjloader reads, a later colour.
  std::string body = test::grid_attributes(5);
  for (int y = 0; y + 1 < 5; ++y)
    for (int x = 0; x + 1 < 5; ++x) body += test::cell(5, x, y, x + y);
  body += "vt 0.125 0.375 0.5\nv 1e-3 -2.5E+2 .5\nv 3 4 5 0.1 0.2 0.3\nf 1 2 7 6\nf 1/2 3/4 8/9 12/13 11/14\n";
  const std::string prefix = "g a b\ns 3\n";
  ASSERT_TRUE(plain(body));
  const ChunkScan scan = scan_chunk(body, 0, body.size());

  ChunkParse fast;
  parse_plain_chunk(body, scan, FaceState{}, &fast);
  expect_same(fast, load_obj("", body), "no state lines");

  const ChunkParse whole = load_obj(prefix, body);
  ASSERT_EQ(whole.shapes.size(), 1u);
  const tinyobj::mesh_t& m = whole.shapes[0].mesh;
  EXPECT_EQ(whole.shapes[0].name, "a b");
  EXPECT_EQ(m.smoothing_group_ids.front(), 3u);
  EXPECT_EQ(m.num_face_vertices.back(), 5);
  EXPECT_EQ(m.indices.back().vertex_index, 10);  // 11, from 1
  EXPECT_EQ(m.indices.back().texcoord_index, 13);
  EXPECT_EQ(m.indices.back().normal_index, -1);
  parse_plain_chunk(body, scan, FaceState{"a b", -1, 3}, &fast);
  expect_same(fast, whole, "behind g and s");

  // Corners of a position alone read by atoi in both parsers: signs,
  // leading zeros and trailing characters alike; one that reads 0, which
  // LoadObj refuses, is refused.
  const std::string odd = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf +1 02 3x\n";
  ASSERT_TRUE(plain(odd));
  parse_plain_chunk(odd, scan_chunk(odd, 0, odd.size()), FaceState{}, &fast);
  expect_same(fast, load_obj("", odd), "odd position corners");
  for (const std::string zero : {"f 0 1 2\n", "f 1 x 2\n"}) {
    ASSERT_TRUE(plain(zero)) << zero;
    parse_plain_chunk(zero, scan_chunk(zero, 0, zero.size()), FaceState{}, &fast);
    EXPECT_FALSE(fast.ok) << zero;
    EXPECT_FALSE(load_obj("", zero).ok) << zero;
  }

  // No faces: no shape; the vertices alone.
  const std::string vertices = "v 1 2 3\nvn 0 1 0\n";
  parse_plain_chunk(vertices, scan_chunk(vertices, 0, vertices.size()), FaceState{}, &fast);
  EXPECT_TRUE(fast.shapes.empty());
  expect_same(fast, load_obj("", vertices), "vertices only");
}

size_t faces_read_from(const std::string& text) { return scan_chunk(text, 0, text.size()).faces_read_from; }

TEST(ObjPlainChunk, TheScanLetsTheFacesBeReadWhereAllNumbersComeFirst) {
  // From the first face line on (its offset in the chunk): faces of corners
  // i, i/j, i//k, i/j/k, comments, blank and unknown lines, tabs, "\r\n".
  EXPECT_EQ(faces_read_from("v 1 2 3\nvt 0 1\nvn 0 0 1\n  f 1/1/1 2//1 3/1\n# c\n\nf\t1 2 3 4\r\nvp 1\n"), 24u);
  EXPECT_EQ(faces_read_from("f 123456789 2 3\n"), 0u);
  const size_t none = ChunkScan::none;
  // Not read: no face; a v, vt or vn line after the first face; a corner
  // that is not a decimal from 1 (a position alone too: atoi reads "02",
  // "3x" and "+1" as tinyobjloader's callbacks do, so they stay with it);
  // a chunk that is not plain.
  for (const char* text : {"v 1 2 3\n", "f 1 2 3\nv 1 2 3\n", "f 1 2 3\nvt 0 0\n", "f 1 2 3\nvn 0 0 1\n", "f 1 02 3\n",
                           "f 1 2 3x\n", "f +1 2 3\n", "f 1 2 3\nf 1 2 # 3\n", "f 0 1 2\n", "f 1 2 1234567890\n",
                           "s 1\nf 1 2 3\n", "f 1/0/1 2/1/1 3/1/1\n"})
    EXPECT_EQ(faces_read_from(text), none) << text;
}

TEST(ObjPlainChunk, FacesReadAfterTheNumbersAreWhatLoadObjGives) {
  // The grid's numbers, then its cells in every corner style, polygons,
  // comments and blank lines among them, "\r\n" line ends.
  std::string body = test::grid_attributes(6);
  std::string triangles_only = body;
  for (int y = 0; y + 1 < 6; ++y)
    for (int x = 0; x + 1 < 6; ++x) {
      body += test::cell(6, x, y, x + 2 * y);
      triangles_only += test::cell(6, x, y, x + 2 * y);
      if ((x + y) % 4 == 0) body += "# between\n\r\nf 1/1 2/2\t8/8 7/7\r\n";
    }
  for (const std::string& text : {body, triangles_only}) {
    const ChunkScan scan = scan_chunk(text, 0, text.size());
    ASSERT_TRUE(scan.plain);
    ASSERT_NE(scan.faces_read_from, ChunkScan::none);
    ChunkParse fast;
    parse_plain_chunk(text, scan, FaceState{"s", -1, 5}, &fast);
    expect_same(fast, load_obj("g s\ns 5\n", text), "faces read after the numbers");
    ASSERT_EQ(fast.shapes.size(), 1u);
    EXPECT_EQ(fast.shapes[0].mesh.smoothing_group_ids.back(), 5u);
  }
  // Into a target: the triangles in place.
  const ChunkScan scan = scan_chunk(triangles_only, 0, triangles_only.size());
  const ChunkParse want = load_obj("", triangles_only);
  ASSERT_EQ(want.shapes.size(), 1u);
  const tinyobj::mesh_t& w = want.shapes[0].mesh;
  const size_t faces = w.num_face_vertices.size();
  std::vector<tinyobj::index_t> corners(3 * faces);
  std::vector<unsigned char> face_corners(faces);
  std::vector<int> materials(faces);
  std::vector<unsigned int> groups(faces);
  ChunkParse into;
  parse_plain_chunk_into(triangles_only, scan, FaceState{},
                         {corners.data(), face_corners.data(), materials.data(), groups.data(), faces}, &into);
  EXPECT_TRUE(into.ok);
  ASSERT_EQ(corners.size(), w.indices.size());
  for (size_t c = 0; c < corners.size(); ++c) {
    EXPECT_EQ(corners[c].vertex_index, w.indices[c].vertex_index) << c;
    EXPECT_EQ(corners[c].texcoord_index, w.indices[c].texcoord_index) << c;
    EXPECT_EQ(corners[c].normal_index, w.indices[c].normal_index) << c;
  }
  EXPECT_EQ(face_corners, w.num_face_vertices);
  EXPECT_EQ(materials, w.material_ids);
  EXPECT_EQ(groups, w.smoothing_group_ids);
  EXPECT_TRUE(same_bits(into.attrib.vertices, want.attrib.vertices));
  // One face too many for the target: refused.
  parse_plain_chunk_into(triangles_only, scan, FaceState{},
                         {corners.data(), face_corners.data(), materials.data(), groups.data(), faces - 1}, &into);
  EXPECT_FALSE(into.ok);
}

}  // namespace
}  // namespace rayform::obj
