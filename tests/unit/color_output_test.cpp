// Colour written to files (src/render/color_output.h): an asset's (linear)
// colour is sRGB-encoded in 8-bit files and kept linear and unclamped in float
// files; a course scene's (display) values are written as they are; --color
// raw|srgb forces either; 8-bit render buffers are written only where their
// encoding is the file's. Exposure scales all colour, the tone map changes
// 8-bit colour only, once, whether the render quantised it or the writer.
#include "rayform/image/color.h"
#include "rayform/image/quantize.h"
#include "rayform/image/tone_map.h"
#include "rayform/render/color_output.h"
#include "rayform/base/error.h"
#include "rayform/render/prepared_scene.h"
#include "test_paths.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace rayform {
namespace {
namespace fs = std::filesystem;

constexpr ColorOutput linear{SceneColors::linear, ColorEncoding::automatic};
constexpr ColorOutput display{SceneColors::display, ColorEncoding::automatic};

// Two pixels: one above 1 in red, one with a negative and a tiny value.
const std::vector<float> values = {2.5f, 0.5f, 0.2f, -0.1f, 1.f, 0.0015f};

RenderResult float_result() {
  RenderResult r;
  r.width = 2;
  r.height = 1;
  r.color = Image(2, 1, 3);
  r.color.pixels = values;
  return r;
}

std::vector<float> written(const std::string& path, const ColorOutput& output) {
  RenderResult r = float_result();
  write_color_image(path, r, output);
  return read_image(path).pixels;
}

TEST(ColorOutput, EncodingFollowsTheSceneAndTheFile) {
  EXPECT_TRUE(writes_srgb(linear, "a.png"));
  EXPECT_TRUE(writes_srgb(linear, "a.JPG"));
  EXPECT_TRUE(writes_srgb(linear, "a.bmp"));
  EXPECT_FALSE(writes_srgb(linear, "a.exr"));
  EXPECT_FALSE(writes_srgb(linear, "a.hdr"));
  EXPECT_FALSE(writes_srgb(linear, "a.tif"));
  EXPECT_FALSE(writes_srgb(display, "a.png"));
  EXPECT_FALSE(writes_srgb(display, "a.exr"));
  EXPECT_FALSE(writes_srgb({SceneColors::linear, ColorEncoding::raw}, "a.png"));
  EXPECT_TRUE(writes_srgb({SceneColors::display, ColorEncoding::srgb}, "a.png"));
  EXPECT_TRUE(writes_srgb({SceneColors::linear, ColorEncoding::srgb}, "a.exr"));

  EXPECT_EQ(render_color_format(linear, "a.png"), ColorFormat::srgb8);
  EXPECT_EQ(render_color_format(display, "a.png"), ColorFormat::unit8);
  EXPECT_EQ(render_color_format(linear, "a.exr"), ColorFormat::linear_float);
  EXPECT_EQ(render_color_format(linear, "a.png", "albedo.bmp"), ColorFormat::srgb8);
  EXPECT_EQ(render_color_format(linear, "a.png", "albedo.exr"), ColorFormat::linear_float);
  EXPECT_EQ(render_color_format(linear, "a.exr", "albedo.png"), ColorFormat::linear_float);
}

TEST(ColorOutput, LinearSceneFloatFilesHoldLinearUnclampedValues) {
  const fs::path dir = test::temp_dir("color_output_float");
  EXPECT_EQ(written((dir / "a.exr").string(), linear), values);  // 2.5 and -0.1 exactly, not clamped
  EXPECT_EQ(written((dir / "a.tif").string(), linear), values);
  // Radiance HDR: 8-bit mantissas under a shared exponent. It holds no
  // negatives: -0.1 is written as 0 (stb alone wrote 1.906).
  const std::vector<float> hdr = written((dir / "a.hdr").string(), linear);
  ASSERT_EQ(hdr.size(), values.size());
  EXPECT_EQ(hdr[0], 2.5f);
  EXPECT_NEAR(hdr[1], 0.5f, 0.5f / 128);
  EXPECT_EQ(hdr[3], 0.f);
  EXPECT_EQ(hdr[4], 1.f);
  fs::remove_all(dir);
}

TEST(ColorOutput, LinearScene8BitFilesHoldSrgbBytes) {
  const fs::path dir = test::temp_dir("color_output_8bit");
  const std::vector<float> png = written((dir / "a.png").string(), linear);
  ASSERT_EQ(png.size(), values.size());
  for (size_t i = 0; i < values.size(); ++i)
    EXPECT_EQ(png[i] * 255.f, float(quantize_srgb_direct(values[i]))) << "sample " << i;
  EXPECT_EQ(png[1] * 255.f, 187.f);  // sRGB(0.5) = 0.7354
  fs::remove_all(dir);
}

TEST(ColorOutput, DisplaySceneIsWrittenRaw) {
  const fs::path dir = test::temp_dir("color_output_display");
  EXPECT_EQ(written((dir / "a.exr").string(), display), values);
  const std::vector<float> png = written((dir / "a.png").string(), display);
  ASSERT_EQ(png.size(), values.size());
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(png[i] * 255.f, float(quantize_unit(values[i])));
  fs::remove_all(dir);
}

TEST(ColorOutput, ForcedEncodings) {
  const fs::path dir = test::temp_dir("color_output_forced");
  // srgb in a float file: encoded, clamped to [0, 1] first.
  const std::vector<float> srgb = written((dir / "a.exr").string(), {SceneColors::linear, ColorEncoding::srgb});
  ASSERT_EQ(srgb.size(), values.size());
  EXPECT_EQ(srgb[0], linear_to_srgb(1.f));  // 0.99999994
  EXPECT_EQ(srgb[1], linear_to_srgb(0.5f));
  EXPECT_EQ(srgb[3], 0.f);
  // raw in an 8-bit file: floor(clamp(v) * 255).
  const std::vector<float> raw = written((dir / "a.png").string(), {SceneColors::linear, ColorEncoding::raw});
  EXPECT_EQ(raw[1] * 255.f, 127.f);
  fs::remove_all(dir);
}

TEST(ColorOutput, EightBitRenderBuffersAreWrittenOnlyInTheirEncoding) {
  const fs::path dir = test::temp_dir("color_output_buffers");
  RenderResult r;
  r.width = 2;
  r.height = 1;
  r.color_format = ColorFormat::srgb8;
  r.color8 = Image8{2, 1, 3, {10, 20, 30, 40, 50, 60}};
  const std::string png = (dir / "a.png").string();
  write_color_image(png, r, linear);
  const DecodedImage back = read_image_file(png);
  EXPECT_EQ(back.bytes, r.color8.pixels);
  EXPECT_THROW(write_color_image((dir / "b.png").string(), r, display), Error);  // raw wanted, sRGB held
  EXPECT_THROW(write_color_image((dir / "c.exr").string(), r, linear), Error);   // floats wanted
  EXPECT_FALSE(fs::exists(dir / "b.png"));
  EXPECT_FALSE(fs::exists(dir / "c.exr"));
  RenderResult none = float_result();
  EXPECT_THROW(write_color_temporary(png, none, ColorPlane::albedo, linear), Error);  // no albedo rendered
  fs::remove_all(dir);
}

TEST(ColorOutput, SrgbEncodingKeepsAlpha) {
  Image rgba(1, 1, 4);
  rgba.pixels = {0.5f, 2.f, -1.f, 0.25f};
  encode_srgb_in_place(rgba);
  EXPECT_EQ(rgba.pixels[0], linear_to_srgb(0.5f));
  EXPECT_EQ(rgba.pixels[1], linear_to_srgb(1.f));
  EXPECT_EQ(rgba.pixels[2], 0.f);
  EXPECT_EQ(rgba.pixels[3], 0.25f);
}

TEST(ColorOutput, ToneMapGoesInto8BitFilesFromFloatColourOnly) {
  const fs::path dir = test::temp_dir("color_output_tone_map");
  RenderResult r = float_result();
  r.tone_map = ToneMap::khr_neutral;
  const std::string exr = (dir / "a.exr").string(), png = (dir / "a.png").string();
  write_color_image(exr, r, linear);
  EXPECT_EQ(read_image(exr).pixels, values);  // float files stay linear
  write_color_image(png, r, linear);
  const std::vector<float> bytes = read_image(png).pixels;
  ASSERT_EQ(bytes.size(), values.size());
  for (size_t i = 0; i < values.size(); i += 3) {
    const vec3 mapped = tone_map_khr_neutral(vec3(values[i], values[i + 1], values[i + 2]));
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(bytes[i + size_t(k)] * 255.f, float(quantize_srgb_direct(mapped[k]))) << "sample " << i + size_t(k);
  }
  EXPECT_EQ(r.tone_map, ToneMap::none);  // r.color now holds mapped (and encoded) colour: not mapped again
  // Albedo is never tone mapped.
  RenderResult a = float_result();
  a.albedo = a.color;
  a.tone_map = ToneMap::aces;
  const std::string albedo_png = (dir / "albedo.png").string();
  commit_temporary(write_color_temporary(albedo_png, a, ColorPlane::albedo, linear), albedo_png);
  const std::vector<float> albedo = read_image(albedo_png).pixels;
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(albedo[i] * 255.f, float(quantize_srgb_direct(values[i])));
  fs::remove_all(dir);
}

// The lit sphere rendered with `o` (48x48).
RenderResult render_sphere(RenderOptions o, AlphaMode alpha = AlphaMode::none) {
  const Scene s = test::lit_sphere_scene(vec3(0.2f, 0.3f, 0.9f));
  const PreparedScene p = prepare_scene(s);
  o.width = o.height = 48;
  o.alpha = alpha;
  return render(p, o);
}

TEST(ColorOutput, ExposureScalesColourNotAlbedo) {
  RenderOptions o;
  o.albedo = true;
  const RenderResult base = render_sphere(o);
  o.exposure_ev = 1.5f;
  o.tone_map = ToneMap::aces;  // float colour: not tone mapped by the render
  const RenderResult exposed = render_sphere(o);
  ASSERT_EQ(exposed.color.pixels.size(), base.color.pixels.size());
  const float scale = std::exp2(1.5f);
  for (size_t i = 0; i < base.color.pixels.size(); ++i)
    EXPECT_FLOAT_EQ(exposed.color.pixels[i], base.color.pixels[i] * scale) << i;
  EXPECT_EQ(exposed.albedo.pixels, base.albedo.pixels);
  EXPECT_EQ(exposed.tone_map, ToneMap::aces);  // left for a writer of 8-bit files
}

TEST(ColorOutput, EightBitRenderEqualsFloatRenderWrittenTo8Bit) {
  // The render loop's tone map and quantisation (srgb8, unit8) give the bytes
  // the writer gives the same render in floats; exposure 0 and no tone map
  // give today's bytes (the quantised float render).
  for (ColorFormat format : {ColorFormat::srgb8, ColorFormat::unit8})
    for (ToneMap map : {ToneMap::none, ToneMap::khr_neutral, ToneMap::aces})
      for (float ev : {0.f, -1.f, 2.f})
        for (int spp : {1, 4}) {
          RenderOptions o;
          o.spp = spp;
          o.exposure_ev = ev;
          o.tone_map = map;
          RenderResult linear_result = render_sphere(o);
          o.color_format = format;
          const RenderResult bytes = render_sphere(o);
          tone_map_in_place(linear_result.color, linear_result.tone_map);
          const std::vector<float>& c = linear_result.color.pixels;
          ASSERT_EQ(bytes.color8.pixels.size(), c.size());
          size_t differ = 0;
          for (size_t i = 0; i < c.size(); ++i)
            differ += bytes.color8.pixels[i] !=
                      (format == ColorFormat::srgb8 ? quantize_srgb_direct(c[i]) : quantize_unit(c[i]));
          EXPECT_EQ(differ, 0u) << tone_map_name(map) << " ev " << ev << " spp " << spp;
        }
}

TEST(ColorOutput, ToneMapKeepsStraightAlpha) {
  RenderOptions o;
  o.spp = 4;
  o.color_format = ColorFormat::srgb8;
  const RenderResult plain = render_sphere(o, AlphaMode::straight);
  o.tone_map = ToneMap::khr_neutral;
  o.exposure_ev = 1.f;
  const RenderResult mapped = render_sphere(o, AlphaMode::straight);
  EXPECT_EQ(mapped.coverage, plain.coverage);
  // The straight colour of the float render, exposed and mapped, is what the 8-bit render holds.
  o.color_format = ColorFormat::linear_float;
  const RenderResult linear_result = render_sphere(o, AlphaMode::straight);
  for (size_t p = 0; p < linear_result.coverage.size(); ++p) {
    const float* c = &linear_result.color.pixels[3 * p];
    const vec3 m = tone_map_khr_neutral(vec3(c[0], c[1], c[2]));
    for (int k = 0; k < 3; ++k) ASSERT_EQ(mapped.color8.pixels[3 * p + size_t(k)], quantize_srgb_direct(m[k])) << p;
  }
}

}  // namespace
}  // namespace rayform
