// Texture decoding and lookup (src/render/texture_sampler.h). The course
// convention: x = u W, y = (1 - v) H, bilinear between (floor x, floor y) and
// (+1, +1) with indices clamped, i.e. texel centres on whole numbers (half a
// texel off the usual convention); the standard convention for assets.
#include "rayform/image/image.h"
#include "rayform/render/texture_sampler.h"
#include "test_paths.h"

#include <gtest/gtest.h>

namespace rayform {
namespace {

// A W x H RGB texture whose texel (x, y) (row 0 = top) holds
// (10 x + 1, 10 y + 2, 7) / 255: every texel distinct, exact as floats / 255.
Texture make_texture(int w, int h, Texture::Lookup lookup) {
  Texture t;
  t.width = w;
  t.height = h;
  t.channels = 3;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t.pixels.insert(t.pixels.end(), {uint8_t(10 * x + 1), uint8_t(10 * y + 2), 7});
  t.lookup = lookup;
  t.wrap_u = t.wrap_v = lookup == Texture::Lookup::course ? Texture::Wrap::clamp : Texture::Wrap::repeat;
  return t;
}

vec4 texel(int x, int y) { return vec4((10.f * x + 1) / 255.f, (10.f * y + 2) / 255.f, 7.f / 255.f, 1.f); }

// Bilinear weights are products of small dyadic fractions here, and texel
// values are k/255: sums of four such products are exact to a few roundings
// of values <= 1, so 1e-6 (~8 ulps) separates them from any neighbouring texel
// (which differ by at least 1/255).
constexpr float kTol = 1e-6f;

void expect_color(vec4 got, vec4 want, const char* what) {
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], want[k], kTol) << what << " channel " << k;
}

TEST(TextureSampler, DecodesEmbeddedPixelsTo8BitFractions) {
  TextureImage t = decode_texture(make_texture(4, 2, Texture::Lookup::course));
  ASSERT_EQ(t.width, 4);
  ASSERT_EQ(t.height, 2);
  EXPECT_EQ(t.rgba8.size(), 4u * 2u * 4u) << "8-bit pixels are kept at 8 bits, as RGBA";
  const vec4 p = t.texel(3, 1);
  EXPECT_EQ(p[0], 31.f / 255.f);
  EXPECT_EQ(p[1], 12.f / 255.f);
  EXPECT_EQ(p[2], 7.f / 255.f);
  EXPECT_EQ(p[3], 1.f);
  EXPECT_EQ(t.lookup, Texture::Lookup::course);
  EXPECT_EQ(t.wrap_u, Texture::Wrap::clamp);
}

TEST(TextureSampler, CourseTexelCentresAreOnWholeNumbers) {
  // 4 x 2 texture: x = 4u, y = 2 (1 - v).
  TextureImage t = decode_texture(make_texture(4, 2, Texture::Lookup::course));
  // (u, v) = (0, 1): x = y = 0 -> exactly texel (0, 0), the top-left.
  expect_color(sample_texture(t, {0.f, 1.f}), texel(0, 0), "u=0 v=1");
  // u = 0.25, v = 0.5: x = 1, y = 1 -> texel (1, 1).
  expect_color(sample_texture(t, {0.25f, 0.5f}), texel(1, 1), "u=.25 v=.5");
  // u = 1/8: x = 0.5, the midpoint of texels 0 and 1 (the standard
  // convention would give texel 0 exactly here).
  expect_color(sample_texture(t, {0.125f, 1.f}), 0.5f * (texel(0, 0) + texel(1, 0)), "u=1/8");
  // x = 1.25, y = 0.5: weights 0.75/0.25 in x, 0.5/0.5 in y.
  vec4 want = 0.5f * (0.75f * texel(1, 0) + 0.25f * texel(2, 0)) + 0.5f * (0.75f * texel(1, 1) + 0.25f * texel(2, 1));
  expect_color(sample_texture(t, {1.25f / 4.f, 1.f - 0.25f}), want, "x=1.25 y=.5");
}

TEST(TextureSampler, CourseIndicesAreClamped) {
  TextureImage t = decode_texture(make_texture(4, 2, Texture::Lookup::course));
  // u = 1, v = 0: x = 4, y = 2, past the last texel: clamps to (3, 1).
  expect_color(sample_texture(t, {1.f, 0.f}), texel(3, 1), "u=1 v=0");
  // x = 3.5 blends texel 3 with the clamped "texel 4" = texel 3.
  expect_color(sample_texture(t, {3.5f / 4.f, 1.f}), texel(3, 0), "x=3.5");
  // Far outside: the nearest edge texel, no wrapping.
  expect_color(sample_texture(t, {-3.f, 5.f}), texel(0, 0), "u=-3 v=5");
  expect_color(sample_texture(t, {7.f, -2.f}), texel(3, 1), "u=7 v=-2");
  expect_color(sample_texture(t, {1.0e30f, -1.0e30f}), texel(3, 1), "huge");
  expect_color(sample_texture(t, {-1.0e30f, 1.0e30f}), texel(0, 0), "huge negative");
  // Just below zero: x = -0.5 -> halfway between "texel -1" (= 0) and 0.
  expect_color(sample_texture(t, {-0.125f, 1.f}), texel(0, 0), "x=-0.5");
}

TEST(TextureSampler, CourseLookupOfNonFiniteUvStaysInsideTheTexture) {
  // uv from a broken OBJ (vt 1e40) are infinite: the result must still be a
  // texel colour, not NaN.
  TextureImage t = decode_texture(make_texture(4, 2, Texture::Lookup::course));
  for (vec2 uv : {vec2(infinity, 0.5f), vec2(0.5f, -infinity), vec2(std::nanf(""), 0.5f)}) {
    vec4 c = sample_texture(t, uv);
    for (int k = 0; k < 4; ++k) {
      EXPECT_TRUE(std::isfinite(c[k])) << "uv (" << uv.x << ", " << uv.y << ") channel " << k;
      EXPECT_GE(c[k], 0.f);
      EXPECT_LE(c[k], 1.f);
    }
  }
}

TEST(TextureSampler, StandardTexelCentresAreOnHalfIntegers) {
  TextureImage t = decode_texture(make_texture(4, 2, Texture::Lookup::standard));
  // Centre of texel (i, j): u = (i + 0.5) / W, v = 1 - (j + 0.5) / H.
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i)
      expect_color(sample_texture(t, {(i + 0.5f) / 4.f, 1.f - (j + 0.5f) / 2.f}), texel(i, j), "centre");
  // Repeat wrap: u + 1 is the same point; the edge blends with the far side.
  expect_color(sample_texture(t, {1.125f, 0.75f}), texel(0, 0), "u + 1");
  expect_color(sample_texture(t, {0.f, 0.75f}), 0.5f * (texel(3, 0) + texel(0, 0)), "left edge wraps");
}

TEST(TextureSampler, StandardClampMirrorAndNearest) {
  Texture tx = make_texture(4, 2, Texture::Lookup::standard);
  tx.wrap_u = tx.wrap_v = Texture::Wrap::clamp;
  TextureImage clamp = decode_texture(tx);
  expect_color(sample_texture(clamp, {0.f, 0.75f}), texel(0, 0), "clamp left edge");
  expect_color(sample_texture(clamp, {-5.f, 0.75f}), texel(0, 0), "clamp far left");
  tx.wrap_u = tx.wrap_v = Texture::Wrap::mirror;
  TextureImage mirror = decode_texture(tx);
  // u = 1.125: mirrored back to texel 3's centre, x = 4.5 - 0.5 = 4 -> index 4 mirrors to 3.
  expect_color(sample_texture(mirror, {1.125f, 0.75f}), texel(3, 0), "mirror");
  tx.wrap_u = tx.wrap_v = Texture::Wrap::repeat;
  tx.filter = Texture::Filter::nearest;
  TextureImage nearest = decode_texture(tx);
  expect_color(sample_texture(nearest, {0.3f, 0.6f}), texel(1, 0), "nearest");
  expect_color(sample_texture(nearest, {0.99f, 0.01f}), texel(3, 1), "nearest corner");
}

TEST(TextureSampler, GreyAndRgbaChannels) {
  Texture g;
  g.width = 2;
  g.height = 1;
  g.channels = 1;
  g.pixels = {51, 204};
  g.lookup = Texture::Lookup::course;
  TextureImage t = decode_texture(g);
  expect_color(sample_texture(t, {0.5f, 1.f}), vec4(vec3(204.f / 255.f), 1.f), "grey replicated, opaque");
  Texture a = g;
  a.channels = 4;
  a.pixels = {10, 20, 30, 40, 50, 60, 70, 80};
  TextureImage ta = decode_texture(a);
  expect_color(sample_texture(ta, {0.f, 1.f}), vec4(10, 20, 30, 40) / 255.f, "rgba keeps alpha");
}

TEST(TextureSampler, SrgbTexturesAreDecodedToLinear) {
  Texture t;
  t.width = t.height = 1;
  t.channels = 3;
  t.pixels = {0, 188, 255};
  t.srgb = true;
  TextureImage d = decode_texture(t);
  const vec4 p = d.texel(0, 0);
  EXPECT_EQ(p[0], 0.f);
  // sRGB 188/255 = 0.7373 -> linear ((0.7373 + 0.055) / 1.055)^2.4 = 0.5029 (IEC 61966-2-1);
  // float pow against double: a few ulps (1e-6).
  EXPECT_NEAR(p[1], std::pow((188.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
  EXPECT_NEAR(p[2], 1.f, 1e-6f);
  t.srgb = false;
  EXPECT_EQ(decode_texture(t).texel(0, 0)[1], 188.f / 255.f);
}

TEST(TextureSampler, DecodesTextureFilesLikeTheCourse) {
  // A BMP written by our writer and read back: 8-bit values map to v / 255.
  auto dir = test::temp_dir("texture_sampler");
  Image img(3, 2, 3);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      float* p = img.at(x, y);
      p[0] = (10.f * x + 1.5f) / 255.f;  // + 0.5: floor quantisation gives exactly 10 x + 1
      p[1] = (10.f * y + 2.5f) / 255.f;
      p[2] = 7.5f / 255.f;
    }
  write_image((dir / "t.bmp").string(), img);
  Texture t;
  t.path = (dir / "t.bmp").string();
  t.lookup = Texture::Lookup::course;
  TextureImage d = decode_texture(t);
  ASSERT_EQ(d.width, 3);
  ASSERT_EQ(d.height, 2);
  expect_color(sample_texture(d, {2.f / 3.f, 0.5f}), texel(2, 1), "file texel (2, 1)");
  expect_color(sample_texture(d, {0.f, 1.f}), texel(0, 0), "file texel (0, 0): row 0 is the top");
  std::filesystem::remove_all(dir);
}

TEST(TextureSampler, MissingFileIsAnErrorNamingIt) {
  Texture t;
  t.path = "/nonexistent/folder/tex.bmp";
  try {
    decode_texture(t);
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/folder/tex.bmp"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rayform
