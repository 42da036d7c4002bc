// Depth and normal pictures (src/render/aov_images.h) in both course
// conventions. 2012 depth: 1 if t < MIN, 0 if t > MAX, else
// (MAX - t) / (MAX - MIN), near white; 2019: (t - MIN) / (MAX - MIN) clamped,
// near black; background black in both. 2012 normals: (|x|, |y|, |z|) on
// black; 2019: (n + 1) / 2 on 0.5 grey.
#include "rayform/render/aov_images.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

namespace rayform {
namespace {

RenderResult depth_row(std::vector<float> depths) {
  RenderResult r;
  r.width = int(depths.size());
  r.height = 1;
  r.depth = std::move(depths);
  return r;
}

std::vector<float> channel0(const Image& img) {
  std::vector<float> v;
  for (int x = 0; x < img.width; ++x) {
    const float* p = img.at(x, 0);
    EXPECT_EQ(p[0], p[1]);  // grey
    EXPECT_EQ(p[0], p[2]);
    v.push_back(p[0]);
  }
  return v;
}

TEST(AovImages, Depth2012NearIsWhite) {
  // MIN 8, MAX 12.
  RenderResult r = depth_row({5.f, 8.f, 9.f, 10.f, 11.f, 12.f, 13.f, infinity});
  Image img = depth_image(r, 8.f, 12.f, DepthStyle::near_white);
  ASSERT_EQ(img.width, 8);
  ASSERT_EQ(img.height, 1);
  ASSERT_EQ(img.channels, 3);
  EXPECT_EQ(channel0(img), (std::vector<float>{1.f, 1.f, 0.75f, 0.5f, 0.25f, 0.f, 0.f, 0.f}));
}

TEST(AovImages, Depth2019NearIsBlack) {
  RenderResult r = depth_row({5.f, 8.f, 9.f, 10.f, 11.f, 12.f, 13.f, infinity});
  Image img = depth_image(r, 8.f, 12.f, DepthStyle::near_black);
  EXPECT_EQ(channel0(img), (std::vector<float>{0.f, 0.f, 0.25f, 0.5f, 0.75f, 1.f, 1.f, 0.f}));
}

TEST(AovImages, DepthWithFractionalRange) {
  // scene05's range 0.8 .. 1.2; t = 0.9 gives (1.2 - 0.9) / 0.4 in float.
  RenderResult r = depth_row({0.9f});
  float want12 = (1.2f - 0.9f) / (1.2f - 0.8f), want19 = (0.9f - 0.8f) / (1.2f - 0.8f);
  EXPECT_EQ(depth_image(r, 0.8f, 1.2f, DepthStyle::near_white).pixels[0], want12);
  EXPECT_EQ(depth_image(r, 0.8f, 1.2f, DepthStyle::near_black).pixels[0], want19);
  EXPECT_NEAR(want12, 0.75f, 1e-6f);  // sanity of the formula itself (float rounding of 0.3/0.4)
}

RenderResult normal_row(std::vector<vec3> normals) {
  RenderResult r;
  r.width = int(normals.size());
  r.height = 1;
  r.normals = std::move(normals);
  return r;
}

TEST(AovImages, Normals2012AreAbsoluteOnBlack) {
  RenderResult r = normal_row({vec3(-0.6f, 0.8f, 0.f), vec3(0.f, 0.f, -1.f), vec3(0.f)});
  Image img = normals_image(r, NormalStyle::absolute);
  ASSERT_EQ(img.channels, 3);
  const std::vector<float> want = {0.6f, 0.8f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f};
  EXPECT_EQ(img.pixels, want);
}

TEST(AovImages, Normals2019AreOffsetOnGrey) {
  RenderResult r = normal_row({vec3(-0.6f, 0.8f, 0.f), vec3(0.f, 0.f, -1.f), vec3(0.f)});
  Image img = normals_image(r, NormalStyle::offset);
  const std::vector<float> want = {0.5f * (-0.6f + 1.f), 0.5f * (0.8f + 1.f), 0.5f, 0.5f, 0.5f, 0.f, 0.5f, 0.5f, 0.5f};
  EXPECT_EQ(img.pixels, want);
}

TEST(AovImages, RenderedSphereDepthAndNormal) {
  // Unit sphere at the origin seen from z = 10: the centre pixel hits at t = 9
  // with normal +z; the corner pixel misses.
  Scene s;
  Camera c;
  c.center = vec3(0, 0, 10);
  c.direction = vec3(0, 0, -1);
  c.up = vec3(0, 1, 0);
  c.fov_deg = 30.f;
  s.cameras.push_back(c);
  s.spheres.push_back({vec3(0.f), 1.f});
  s.nodes.push_back(test::shape_node(ShapeKind::sphere, 0));
  s.root = 0;
  PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 5;
  o.depth = o.normals = true;
  RenderResult res = render(p, o);
  const size_t centre = 2 * 5 + 2, corner = 0;
  EXPECT_EQ(res.depth[centre], 9.f);
  EXPECT_EQ(res.normals[centre], vec3(0, 0, 1));
  EXPECT_TRUE(std::isinf(res.depth[corner]));
  EXPECT_EQ(res.normals[corner], vec3(0.f));
  Image d12 = depth_image(res, 8.f, 12.f, DepthStyle::near_white),
        d19 = depth_image(res, 8.f, 12.f, DepthStyle::near_black);
  EXPECT_EQ(d12.pixels[3 * centre], 0.75f);
  EXPECT_EQ(d19.pixels[3 * centre], 0.25f);
  EXPECT_EQ(d12.pixels[3 * corner], 0.f);
  EXPECT_EQ(d19.pixels[3 * corner], 0.f);
  Image n12 = normals_image(res, NormalStyle::absolute), n19 = normals_image(res, NormalStyle::offset);
  EXPECT_EQ(n12.pixels[3 * centre + 2], 1.f);
  EXPECT_EQ(n19.pixels[3 * centre + 2], 1.f);
  EXPECT_EQ(n19.pixels[3 * centre + 0], 0.5f);
  EXPECT_EQ(n12.pixels[3 * corner + 1], 0.f);
  EXPECT_EQ(n19.pixels[3 * corner + 1], 0.5f);
}

}  // namespace
}  // namespace rayform
