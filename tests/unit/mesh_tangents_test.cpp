// Tangent generation for normal textures (scene/mesh_tangents.h): the
// analytic tangent and handedness of planar quads, mirrored uvs
// (NormalTangentMirrorTest's case), continuity across the shared vertices of
// a curved strip (welded or not), degenerate uvs, and meshes without uvs.
#include "rayform/scene/mesh_tangents.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rayform {
namespace {

// The unit square in the z = 0 plane, facing +z, two triangles (0 1 2, 0 2 3),
// uvs from the position by `uv_of`.
template <class UvOf>
Mesh square(UvOf uv_of, bool with_normals = true) {
  Mesh m;
  m.positions = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {1.f, 1.f, 0.f}, {0.f, 1.f, 0.f}};
  if (with_normals) m.normals.assign(4, vec3(0.f, 0.f, 1.f));
  for (vec3 p : m.positions) m.uvs.push_back(uv_of(p));
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

void expect_tangent(vec4 got, vec3 tangent, float w, const char* what) {
  EXPECT_NEAR(got.x, tangent.x, 1e-6f) << what;
  EXPECT_NEAR(got.y, tangent.y, 1e-6f) << what;
  EXPECT_NEAR(got.z, tangent.z, 1e-6f) << what;
  EXPECT_EQ(got.w, w) << what;
}

TEST(MeshTangents, SquareGivesTheAnalyticTangentAndHandedness) {
  // u right, v up (a glTF texture laid on the square as seen from +z: glTF v
  // = 1 - v grows downwards, the picture's top at y = 1): t = +x, b = +y =
  // the picture's up = the normal texture's +Y, so w = +1 (b = w cross(n, t)).
  // Scaling u or v changes nothing.
  Mesh m = square([](vec3 p) { return vec2(0.5f * p.x, 2.f * p.y); });
  std::vector<vec4> t = corner_tangents(m, 0);
  ASSERT_EQ(t.size(), 6u);
  for (vec4 c : t) expect_tangent(c, vec3(1.f, 0.f, 0.f), 1.f, "u right, v up");

  // Sheared uvs (u = x + y / 2, v = y): dP/du = +x still, dP/dv = (-1/2, 1, 0).
  m = square([](vec3 p) { return vec2(p.x + 0.5f * p.y, p.y); });
  for (vec4 c : corner_tangents(m, 0)) expect_tangent(c, vec3(1.f, 0.f, 0.f), 1.f, "sheared");

  // Rotated a quarter turn (u = y, v = -x): t = +y, b = -x = cross(+z, +y): w = +1.
  m = square([](vec3 p) { return vec2(p.y, -p.x); });
  for (vec4 c : corner_tangents(m, 0)) expect_tangent(c, vec3(0.f, 1.f, 0.f), 1.f, "rotated");

  // Mirrored in u (u = -x, v = y): t = -x, b = +y = -cross(+z, -x): w = -1.
  m = square([](vec3 p) { return vec2(-p.x, p.y); });
  for (vec4 c : corner_tangents(m, 0)) expect_tangent(c, vec3(-1.f, 0.f, 0.f), -1.f, "mirrored");

  // Flipped in v as a glTF reader that forgot 1 - v would give (v down): w = -1.
  m = square([](vec3 p) { return vec2(p.x, 1.f - p.y); });
  for (vec4 c : corner_tangents(m, 0)) expect_tangent(c, vec3(1.f, 0.f, 0.f), -1.f, "v down");

  // Without normals: the face normal (+z, from the winding) gives the same.
  m = square([](vec3 p) { return vec2(p.x, p.y); }, false);
  for (vec4 c : corner_tangents(m, 0)) expect_tangent(c, vec3(1.f, 0.f, 0.f), 1.f, "face normals");
}

TEST(MeshTangents, MirroredHalvesSharingASeamKeepTheirOwnTangents) {
  // Two squares side by side, x in [-1, 0] and [0, 1], sharing the seam's two
  // vertices (same position, normal and uv: u = |x|, v = y): the left half's
  // uvs are mirrored. Its corners, the seam's included, get t = -x, w = -1;
  // the right half's t = +x, w = +1 (averaged together, the seam's tangents
  // would cancel).
  Mesh m;
  m.positions = {{-1.f, 0.f, 0.f}, {0.f, 0.f, 0.f}, {1.f, 0.f, 0.f},
                 {-1.f, 1.f, 0.f}, {0.f, 1.f, 0.f}, {1.f, 1.f, 0.f}};
  m.normals.assign(6, vec3(0.f, 0.f, 1.f));
  for (vec3 p : m.positions) m.uvs.push_back(vec2(std::abs(p.x), p.y));
  m.indices = {0, 1, 4, 0, 4, 3,   // left
               1, 2, 5, 1, 5, 4};  // right
  std::vector<vec4> t = corner_tangents(m, 0);
  ASSERT_EQ(t.size(), 12u);
  for (int c = 0; c < 6; ++c) expect_tangent(t[size_t(c)], vec3(-1.f, 0.f, 0.f), -1.f, "left (mirrored)");
  for (int c = 6; c < 12; ++c) expect_tangent(t[size_t(c)], vec3(1.f, 0.f, 0.f), 1.f, "right");
}

// A strip around the y axis: segments + 1 columns at angle theta_k = k
// 2 pi / segments (the first and last at the same place, u 0 and 1), two rows
// y = 0 and 1; P = (sin theta, y, cos theta), n = (sin theta, 0, cos theta),
// u = theta / (2 pi), v = y, wound outwards.
Mesh cylinder_strip(int segments) {
  Mesh m;
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k <= segments; ++k) {
      float theta = 2.f * pi * float(k) / float(segments);
      m.positions.push_back(vec3(std::sin(theta), float(row), std::cos(theta)));
      m.normals.push_back(vec3(std::sin(theta), 0.f, std::cos(theta)));
      m.uvs.push_back(vec2(float(k) / float(segments), float(row)));
    }
  uint32_t columns = uint32_t(segments + 1);
  for (uint32_t k = 0; k < uint32_t(segments); ++k) {
    uint32_t a = k, b = k + 1, c = columns + k + 1, d = columns + k;
    m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
  }
  return m;
}

// dP/du's direction on the strip at angle theta.
vec3 strip_tangent(float theta) { return vec3(std::cos(theta), 0.f, -std::sin(theta)); }

TEST(MeshTangents, CurvedStripHasContinuousTangents) {
  const int segments = 12;
  Mesh m = cylinder_strip(segments);
  std::vector<vec4> t = corner_tangents(m, 0);
  ASSERT_EQ(t.size(), m.indices.size());
  std::vector<vec4> at_vertex(m.positions.size(), vec4(0.f));
  for (size_t c = 0; c < t.size(); ++c) {
    uint32_t index = m.indices[c];
    int k = int(index % uint32_t(segments + 1));
    float theta = 2.f * pi * float(k) / float(segments);
    vec3 expected = strip_tangent(theta);
    EXPECT_NEAR(glm::length(vec3(t[c]) - expected), 0.f, 2e-6f) << "vertex " << index;
    EXPECT_EQ(t[c].w, 1.f);
    EXPECT_NEAR(glm::dot(vec3(t[c]), m.normals[index]), 0.f, 1e-6f);
    // Every corner of one vertex has the one tangent.
    if (at_vertex[index] == vec4(0.f)) at_vertex[index] = t[c];
    EXPECT_EQ(t[c], at_vertex[index]) << "vertex " << index;
  }

  // The same strip unwelded (each corner its own vertex, as a file without
  // indices): corners with equal position, normal and uv are still one
  // vertex of the tangent space, so the tangents are the same.
  Mesh unwelded;
  for (uint32_t index : m.indices) {
    unwelded.indices.push_back(uint32_t(unwelded.positions.size()));
    unwelded.positions.push_back(m.positions[index]);
    unwelded.normals.push_back(m.normals[index]);
    unwelded.uvs.push_back(m.uvs[index]);
  }
  EXPECT_EQ(corner_tangents(unwelded, 0), t);
}

TEST(MeshTangents, DegenerateUvsGiveUnitTangentsPerpendicularToTheNormal) {
  // All three uvs equal, and uvs on a line (v constant): no tangent from the
  // uvs; any unit vector perpendicular to n, w = +1.
  const std::vector<vec2> degenerate_uvs[] = {{vec2(0.25f, 0.5f), vec2(0.25f, 0.5f), vec2(0.25f, 0.5f)},
                                              {vec2(0.25f, 0.5f), vec2(0.75f, 0.5f), vec2(1.f, 0.5f)}};
  for (const std::vector<vec2>& uvs : degenerate_uvs) {
    Mesh m;
    m.positions = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 1.f}};
    vec3 n = glm::normalize(vec3(0.f, -1.f, 1.f));
    m.normals.assign(3, n);
    m.uvs = uvs;
    m.indices = {0, 1, 2};
    std::vector<vec4> t = corner_tangents(m, 0);
    ASSERT_EQ(t.size(), 3u);
    for (vec4 c : t) {
      ASSERT_TRUE(is_finite(vec3(c)));
      EXPECT_NEAR(glm::length(vec3(c)), 1.f, 1e-6f);
      EXPECT_NEAR(glm::dot(vec3(c), n), 0.f, 1e-6f);
      EXPECT_EQ(c.w, 1.f);
    }
  }
  // A degenerate triangle beside a good one takes the good one's tangent at
  // the vertices they share (its third corner has none to take).
  Mesh m = square([](vec3 p) { return vec2(p.x, p.y); });
  m.positions.push_back(vec3(-1.f, 0.5f, 0.f));
  m.normals.push_back(vec3(0.f, 0.f, 1.f));
  m.uvs.push_back(vec2(0.f, 0.f));  // equal to vertex 0's: the triangle 0 3 4 has uvs on a line
  m.indices.insert(m.indices.end(), {0, 3, 4});
  std::vector<vec4> t = corner_tangents(m, 0);
  ASSERT_EQ(t.size(), 9u);
  expect_tangent(t[6], vec3(1.f, 0.f, 0.f), 1.f, "shared corner 0");
  expect_tangent(t[7], vec3(1.f, 0.f, 0.f), 1.f, "shared corner 3");
  EXPECT_NEAR(glm::length(vec3(t[8])), 1.f, 1e-6f);
  EXPECT_NEAR(t[8].z, 0.f, 1e-6f);
  EXPECT_EQ(t[8].w, 1.f);
}

TEST(MeshTangents, UvSetsAndMeshesWithoutUvs) {
  Mesh m = square([](vec3 p) { return vec2(p.x, p.y); });
  // Set 1: its own uvs (here rotated: u = y, v = -x).
  for (vec3 p : m.positions) m.uvs1.push_back(vec2(p.y, -p.x));
  for (vec4 c : corner_tangents(m, 1)) expect_tangent(c, vec3(0.f, 1.f, 0.f), 1.f, "set 1");
  for (vec4 c : corner_tangents(m, 0)) expect_tangent(c, vec3(1.f, 0.f, 0.f), 1.f, "set 0");
  // No uvs of the set (or not one per position): no tangents.
  EXPECT_TRUE(corner_tangents(m, 2).empty());
  m.uvs1.clear();
  EXPECT_TRUE(corner_tangents(m, 1).empty());
  m.uvs.pop_back();
  EXPECT_TRUE(corner_tangents(m, 0).empty());
  m.uvs.clear();
  EXPECT_TRUE(corner_tangents(m, 0).empty());
}

}  // namespace
}  // namespace rayform
