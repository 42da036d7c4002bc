// 8-bit quantisation (src/image/quantize.h): the direct rule, the sRGB
// threshold table against the direct formula, and the render loop's 8-bit
// outputs against quantising its float output afterwards.
#include "rayform/image/quantize.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/importers/scene_io.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

namespace rayform {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
const float nan = std::numeric_limits<float>::quiet_NaN();

TEST(Quantize, UnitRuleIsFloorOfClampedTimes255) {
  EXPECT_EQ(quantize_unit(0.f), 0);
  EXPECT_EQ(quantize_unit(1.f), 255);
  EXPECT_EQ(quantize_unit(0.5f), 127);
  EXPECT_EQ(quantize_unit(std::nextafter(1.f, 0.f)), 254);
  EXPECT_EQ(quantize_unit(-3.f), 0);
  EXPECT_EQ(quantize_unit(7.f), 255);
  EXPECT_EQ(quantize_unit(inf), 255);
  EXPECT_EQ(quantize_unit(-inf), 0);
  EXPECT_EQ(quantize_unit(nan), 0);
}

TEST(Quantize, SrgbSpecialValues) {
  const SrgbQuantizer& q = srgb_quantizer();
  for (float v : {0.f, -0.f, 1.f, 0.5f, 0.0031308f, 0.2f, -1.f, 2.f, inf, -inf, nan, 1e-30f})
    EXPECT_EQ(q(v), quantize_srgb_direct(v)) << v;
  EXPECT_EQ(q(0.5f), 187);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> floor(187.5)
}

// Around every threshold (where pow's rounding could make the direct formula
// step back), 4096 floats each side.
TEST(Quantize, SrgbTableEqualsTheDirectFormulaAroundEveryThreshold) {
  const SrgbQuantizer& q = srgb_quantizer();
  int finite = 0;
  for (int k = 1; k < 256; ++k) {
    const float t = q.threshold[size_t(k)];
    if (std::isnan(t)) continue;
    ++finite;
    EXPECT_GE(quantize_srgb_direct(t), k);
    EXPECT_LT(quantize_srgb_direct(std::nextafter(t, -inf)), k);
    const uint32_t bits = std::bit_cast<uint32_t>(t);
    for (uint32_t d = 0; d <= 4096; ++d) {
      for (uint32_t b : {bits + d, bits > d ? bits - d : 0u}) {
        const float v = std::bit_cast<float>(b);
        ASSERT_EQ(q(v), quantize_srgb_direct(v)) << "v " << v << " near threshold " << k;
      }
    }
  }
  EXPECT_EQ(finite, 255);  // every value is reached, 255 at 1 exactly
  EXPECT_EQ(quantize_srgb_direct(1.f), 255);
  EXPECT_EQ(quantize_srgb_direct(std::nextafter(1.f, 0.f)), 254);
  EXPECT_EQ(q(1.f), 255);
  EXPECT_EQ(q(inf), 255);
}

// The lookup compares with one threshold only: every bucket of 2^16 floats
// must span at most one step, and its first and last floats must agree.
TEST(Quantize, EverySrgbBucketSpansAtMostOneStep) {
  const SrgbQuantizer& q = srgb_quantizer();
  for (size_t b = 1; b < SrgbQuantizer::buckets - 1; ++b) {
    const float first = std::bit_cast<float>(uint32_t(b) << SrgbQuantizer::bucket_shift);
    const float last = std::bit_cast<float>((uint32_t(b + 1) << SrgbQuantizer::bucket_shift) - 1u);
    ASSERT_EQ(q.bucket_level[b], quantize_srgb_direct(first)) << b;
    ASSERT_LE(quantize_srgb_direct(last) - q.bucket_level[b], 1) << b;
    ASSERT_EQ(q(first), quantize_srgb_direct(first)) << b;
    ASSERT_EQ(q(last), quantize_srgb_direct(last)) << b;
  }
}

TEST(Quantize, SrgbTableEqualsTheDirectFormulaOnRandomInputs) {
  const SrgbQuantizer& q = srgb_quantizer();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(-0.1f, 1.1f);
  std::uniform_int_distribution<uint32_t> bits(0u, std::bit_cast<uint32_t>(1.f));  // every exponent alike
  for (int i = 0; i < 1'000'000; ++i) {
    const float a = value(rng), b = std::bit_cast<float>(bits(rng));
    ASSERT_EQ(q(a), quantize_srgb_direct(a)) << a;
    ASSERT_EQ(q(b), quantize_srgb_direct(b)) << b;
  }
}

// The render loop's 8-bit colour and albedo are its float ones quantised.
TEST(Quantize, RenderLoop8BitOutputsEqualQuantisedFloatOutputs) {
  LoadedScene l = load_scene((test::source_dir() / "scenes" / "tests" / "textures_transformed.txt").string());
  PreparedScene p = prepare_scene(l.scene);
  RenderOptions o;
  o.width = 37;
  o.height = 29;
  o.shadows = true;
  o.spp = 4;
  o.albedo = true;
  const RenderResult linear = render(p, o);
  for (ColorFormat format : {ColorFormat::unit8, ColorFormat::srgb8}) {
    o.color_format = format;
    const RenderResult q = render(p, o);
    EXPECT_TRUE(q.color.empty());
    EXPECT_TRUE(q.albedo.empty());
    ASSERT_EQ(q.color8.pixels.size(), linear.color.pixels.size());
    ASSERT_EQ(q.albedo8.pixels.size(), linear.albedo.pixels.size());
    int levels_seen = 0;
    std::array<bool, 256> seen{};
    for (size_t i = 0; i < linear.color.pixels.size(); ++i) {
      const float c = linear.color.pixels[i], a = linear.albedo.pixels[i];
      const uint8_t want_c = format == ColorFormat::srgb8 ? quantize_srgb_direct(c) : quantize_unit(c);
      const uint8_t want_a = format == ColorFormat::srgb8 ? quantize_srgb_direct(a) : quantize_unit(a);
      ASSERT_EQ(q.color8.pixels[i], want_c) << i;
      ASSERT_EQ(q.albedo8.pixels[i], want_a) << i;
      if (!seen[want_c]) ++levels_seen, seen[want_c] = true;
    }
    EXPECT_GT(levels_seen, 20);  // a picture, not a flat field
  }
}

}  // namespace
}  // namespace rayform
