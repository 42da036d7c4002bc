// Colour written to files (src/render/color_output.h): an asset's (linear)
// colour is sRGB-encoded in 8-bit files and kept linear and unclamped in float
// files; a course scene's (display) values are written as they are; --color
// raw|srgb forces either; 8-bit render buffers are written only where their
// encoding is the file's.
#include "rayform/image/color.h"
#include "rayform/image/quantize.h"
#include "rayform/render/color_output.h"
#include "rayform/base/error.h"
#include "test_paths.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace rayform
