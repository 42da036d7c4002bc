// Cube-map lookup (src/render/cube_map.h): the face chosen by the major axis
// and the face coordinates of the course's convention, checked against the
// table in the header written out here once more, direction by direction.
#include "rayform/render/cube_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rayform {
namespace {

// Six 4x4 float faces, nearest lookup, clamped: texel (x, y) of face f holds
// (f, x, y), so a lookup tells which face and which texel it read.
std::vector<TextureImage> make_faces() {
  std::vector<TextureImage> faces(6);
  for (int f = 0; f < 6; ++f) {
    TextureImage& t = faces[size_t(f)];
    t.width = t.height = 4;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) t.rgbaf.insert(t.rgbaf.end(), {float(f), float(x), float(y), 1.f});
    t.wrap_u = t.wrap_v = Texture::Wrap::clamp;
    t.filter = Texture::Filter::nearest;
  }
  return faces;
}

struct Case {
  vec3 direction;
  int face;
  vec2 uv;  // from the table: a = major component, s, t as listed there
};

// (s, t) of the table's per-face formulas, evaluated by hand for directions
// whose components are exact in binary, so every expected uv is exact.
Case cases[] = {
    // +x right: ((z/a + 1)/2, (y/a + 1)/2)
    {{2.f, 1.f, -0.5f}, cube_right, {0.375f, 0.75f}},
    // -x left: ((z/a + 1)/2, 1 - (y/a + 1)/2), a = -2
    {{-2.f, 1.f, -0.5f}, cube_left, {0.625f, 0.75f}},
    // +y up: ((x/a + 1)/2, (z/a + 1)/2)
    {{1.f, 2.f, -0.5f}, cube_up, {0.75f, 0.375f}},
    // -y down: (1 - (x/a + 1)/2, 1 - (z/a + 1)/2), a = -2
    {{1.f, -2.f, -0.5f}, cube_down, {0.75f, 0.375f}},
    // +z front: (1 - (x/a + 1)/2, (y/a + 1)/2)
    {{1.f, -0.5f, 2.f}, cube_front, {0.25f, 0.375f}},
    // -z back: ((x/a + 1)/2, 1 - (y/a + 1)/2), a = -2
    {{1.f, -0.5f, -2.f}, cube_back, {0.25f, 0.375f}},
};

TEST(CubeMap, PicksTheMajorAxisFaceAndTheCourseCoordinates) {
  const std::vector<TextureImage> faces = make_faces();
  for (const Case& c : cases) {
    const vec3 got = sample_cube_map(faces, c.direction);
    const vec3 want(sample_texture(faces[size_t(c.face)], c.uv));
    EXPECT_EQ(got, want) << "direction " << c.direction.x << "," << c.direction.y << "," << c.direction.z;
    EXPECT_EQ(int(got.x), c.face);
  }
}

TEST(CubeMap, OppositeFacesMirrorSAndKeepT) {
  // On -x, a < 0 mirrors both ratios and the table flips t back: the same
  // (y, z) reads mirrored columns and the same row as on +x (s 0.8 and 0.2,
  // t 0.875 on both).
  const std::vector<TextureImage> faces = make_faces();
  const vec3 right = sample_cube_map(faces, {2.f, 1.5f, 1.2f});
  const vec3 left = sample_cube_map(faces, {-2.f, 1.5f, 1.2f});
  EXPECT_EQ(right.x, float(cube_right));
  EXPECT_EQ(left.x, float(cube_left));
  EXPECT_EQ(right.y, 3.f);
  EXPECT_EQ(left.y, 0.f);
  EXPECT_EQ(right.z, left.z);
}

TEST(CubeMap, TiesGoToXThenY) {
  const std::vector<TextureImage> faces = make_faces();
  EXPECT_EQ(sample_cube_map(faces, {1.f, 1.f, 1.f}).x, float(cube_right));
  EXPECT_EQ(sample_cube_map(faces, {0.f, -1.f, 1.f}).x, float(cube_down));
  EXPECT_EQ(sample_cube_map(faces, {0.f, 0.f, -1.f}).x, float(cube_back));
}

TEST(CubeMap, ZeroOrNaNDirectionIsBlack) {
  const std::vector<TextureImage> faces = make_faces();
  EXPECT_EQ(sample_cube_map(faces, vec3(0.f)), vec3(0.f));
  EXPECT_EQ(sample_cube_map(faces, vec3(std::numeric_limits<float>::quiet_NaN())), vec3(0.f));
}

}  // namespace
}  // namespace rayform
