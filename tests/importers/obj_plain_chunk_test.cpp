// The plain chunks of the chunked OBJ parse (obj_plain_chunk.h): which
// chunks the scan calls plain, and that the callback parse of one gives,
// array for array and bit for bit, what tinyobj::LoadObj gives for it.
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

}  // namespace
}  // namespace rayform::obj
