// RenderOptions::alpha: the coverage of each pixel (render.h's AlphaMode) and
// the colour that goes with it, on a sphere against a plain background and on
// a mesh that takes the eight-ray packet path.
#include "rayform/image/quantize.h"
#include "rayform/importers/scene_io.h"
#include "rayform/render/aov_images.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/scene/scene_defaults.h"
#include "test_paths.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace rayform {
namespace {

const vec3 background_color(0.1f, 0.2f, 0.3f);

Scene sphere_scene() { return test::lit_sphere_scene(background_color); }

RenderResult render_with(const PreparedScene& p, int spp, AlphaMode alpha) {
  RenderOptions o;
  o.width = o.height = 32;
  o.spp = spp;
  o.alpha = alpha;
  return render(p, o);
}

vec3 color_at(const RenderResult& r, size_t i) {
  return vec3(r.color.pixels[3 * i], r.color.pixels[3 * i + 1], r.color.pixels[3 * i + 2]);
}

TEST(Coverage, OneSamplePerPixelIsHitOrMiss) {
  const Scene s = sphere_scene();
  const PreparedScene p = prepare_scene(s);
  const RenderResult plain = render_with(p, 1, AlphaMode::none);
  EXPECT_TRUE(plain.coverage.empty());  // not asked: not allocated
  const RenderResult r = render_with(p, 1, AlphaMode::straight);
  ASSERT_EQ(r.coverage.size(), 32u * 32u);
  const size_t centre = 16 * 32 + 16, corner = 0;
  EXPECT_EQ(r.coverage[centre], 1.f);
  EXPECT_EQ(r.coverage[corner], 0.f);
  int covered = 0;
  for (float a : r.coverage) {
    EXPECT_TRUE(a == 0.f || a == 1.f) << a;
    covered += a == 1.f;
  }
  EXPECT_GT(covered, 32 * 32 / 10);
  EXPECT_LT(covered, 32 * 32 / 2);
  // Straight alpha: the colour of every pixel as without alpha (the background where rays miss).
  EXPECT_EQ(std::memcmp(r.color.pixels.data(), plain.color.pixels.data(), plain.color.pixels.size() * sizeof(float)),
            0);
  // Premultiplied: the background black, covered pixels unchanged.
  const RenderResult pre = render_with(p, 1, AlphaMode::premultiplied);
  EXPECT_EQ(pre.coverage, r.coverage);
  EXPECT_EQ(color_at(pre, corner), vec3(0.f));
  EXPECT_EQ(color_at(pre, centre), color_at(plain, centre));
  EXPECT_EQ(color_at(r, corner), background_color);
}

TEST(Coverage, SeveralSamplesGiveTheFractionThatHits) {
  const Scene s = sphere_scene();
  const PreparedScene p = prepare_scene(s);
  const RenderResult plain = render_with(p, 16, AlphaMode::none);
  const RenderResult straight = render_with(p, 16, AlphaMode::straight);
  const RenderResult pre = render_with(p, 16, AlphaMode::premultiplied);
  const size_t centre = 16 * 32 + 16, corner = 0;
  EXPECT_EQ(straight.coverage[centre], 1.f);
  EXPECT_EQ(straight.coverage[corner], 0.f);
  EXPECT_EQ(pre.coverage, straight.coverage);
  // A pixel whose samples all miss is the background exactly, not an
  // average a float step off it (with or without alpha).
  EXPECT_EQ(color_at(plain, corner), background_color);
  EXPECT_EQ(color_at(straight, corner), background_color);
  // The sphere's edge on the centre row: coverage falls from 1 to 0 going
  // out, through at least one pixel in between.
  int edge = -1;
  for (int x = 16; x < 32 && edge < 0; ++x) {
    const float a = straight.coverage[16 * 32 + x];
    if (a > 0.f && a < 1.f) edge = x;
  }
  ASSERT_GE(edge, 0) << "no partly covered pixel on the centre row";
  const size_t e = 16 * 32 + size_t(edge);
  const float a = straight.coverage[e];
  // 16 box-filtered samples: a multiple of 1/16.
  EXPECT_EQ(a * 16.f, std::round(a * 16.f)) << a;
  // Straight over the background gives the plain render; premultiplied is straight times coverage.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(color_at(straight, e)[k] * a + background_color[k] * (1.f - a), color_at(plain, e)[k], 1e-5f);
    EXPECT_NEAR(color_at(pre, e)[k], color_at(straight, e)[k] * a, 1e-5f);
  }
  // Fully covered pixels: the same colour, bit for bit, in all three modes;
  // background pixels: the background (straight) or black (premultiplied).
  for (size_t i = 0; i < straight.coverage.size(); ++i) {
    if (straight.coverage[i] == 1.f) {
      EXPECT_EQ(color_at(straight, i), color_at(plain, i)) << i;
      EXPECT_EQ(color_at(pre, i), color_at(plain, i)) << i;
    } else if (straight.coverage[i] == 0.f) {
      EXPECT_EQ(color_at(straight, i), color_at(plain, i)) << i;
      EXPECT_EQ(color_at(pre, i), vec3(0.f)) << i;
    }
  }
}

TEST(Coverage, EightBitColourWithAlphaChannel) {
  const Scene s = sphere_scene();
  const PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 32;
  o.alpha = AlphaMode::straight;
  o.color_format = ColorFormat::unit8;
  const RenderResult r = render(p, o);
  const Image8 rgba = color8_with_alpha(r);
  ASSERT_EQ(rgba.channels, 4);
  ASSERT_EQ(rgba.pixels.size(), 32u * 32u * 4u);
  const size_t centre = 16 * 32 + 16;
  EXPECT_EQ(rgba.pixels[3], 0);  // corner: transparent, the background's bytes
  for (int k = 0; k < 3; ++k) EXPECT_EQ(rgba.pixels[k], quantize_unit(background_color[k]));
  EXPECT_EQ(rgba.pixels[4 * centre + 3], 255);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(rgba.pixels[4 * centre + k], r.color8.pixels[3 * centre + k]);
  o.color_format = ColorFormat::linear_float;
  const Image f = color_with_alpha(render(p, o));
  ASSERT_EQ(f.channels, 4);
  EXPECT_EQ(f.pixels[3], 0.f);
  EXPECT_EQ(f.pixels[4 * centre + 3], 1.f);
}

// The packet path (a scene of one mesh, one sample) and the one-by-one path
// agree, and a pixel is covered exactly where its centre ray has a depth.
TEST(Coverage, PacketPathMatchesDepth) {
  LoadedScene loaded = load_scene((test::source_dir() / "scenes" / "assets" / "torus.obj").string());
  add_default_camera(loaded.scene);
  add_headlight(loaded.scene, 0);
  const PreparedScene p = prepare_scene(loaded.scene);
  ASSERT_GE(sole_mesh_instance(p), 0);
  RenderOptions o;
  o.width = 61;
  o.height = 47;
  o.depth = true;
  o.alpha = AlphaMode::straight;
  for (bool packets : {true, false}) {
    o.packets = packets;
    const RenderResult r = render(p, o);
    int covered = 0;
    for (size_t i = 0; i < r.coverage.size(); ++i) {
      EXPECT_EQ(r.coverage[i], std::isfinite(r.depth[i]) ? 1.f : 0.f) << i << (packets ? " packets" : "");
      covered += r.coverage[i] == 1.f;
    }
    EXPECT_GT(covered, 61 * 47 / 20);
  }
}

}  // namespace
}  // namespace rayform
