// Tone mapping (src/image/tone_map.h): Khronos PBR Neutral and Hill's ACES
// fit against values worked out by hand from their formulas, their ranges,
// and monotonicity along grey and along one channel.
#include "rayform/image/tone_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rayform {
namespace {

constexpr float tolerance = 1e-5f;  // float rounding of the formulas' few operations

void expect_near(vec3 got, vec3 want) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tolerance) << "channel " << k;
}

TEST(ToneMap, NeutralBelowTheCompressionStartOnlyTakesTheOffset) {
  // min >= 0.08: the offset is F90 = 0.04, and the peak 0.46 < 0.76 is not compressed.
  expect_near(tone_map_khr_neutral(vec3(0.5f)), vec3(0.46f));
  expect_near(tone_map_khr_neutral(vec3(0.7f, 0.3f, 0.1f)), vec3(0.66f, 0.26f, 0.06f));
  // min 0.04 < 0.08: the offset is x - x^2 / 0.16 = 0.04 - 0.01.
  expect_near(tone_map_khr_neutral(vec3(0.04f)), vec3(0.01f));
  expect_near(tone_map_khr_neutral(vec3(0.f)), vec3(0.f));
}

TEST(ToneMap, NeutralCompressesAndDesaturatesHighlights) {
  // White 1: c - f = 0.96, p_n = 1 - 0.24^2 / (0.96 + 0.24 - 0.76) = 1 - 0.0576 / 0.44.
  expect_near(tone_map_khr_neutral(vec3(1.f)), vec3(1.f - 0.0576f / 0.44f));
  // (2, 0.5, 0.1): c - f = (1.96, 0.46, 0.06), p_n = 1 - 0.0576 / 1.44 = 0.96,
  // scaled by 0.96 / 1.96, then mixed towards 0.96 by 1 - 1 / (0.15 * 1 + 1) = 0.15 / 1.15.
  const float scale = 0.96f / 1.96f, mix = 0.15f / 1.15f;
  const vec3 scaled(1.96f * scale, 0.46f * scale, 0.06f * scale);
  expect_near(tone_map_khr_neutral(vec3(2.f, 0.5f, 0.1f)), scaled + mix * (vec3(0.96f) - scaled));
}

TEST(ToneMap, NeutralIsMonotonicAndBelowOne) {
  float previous = -1.f;
  for (float v = 0.f; v < 1000.f; v = v * 1.05f + 0.001f) {
    const float grey = tone_map_khr_neutral(vec3(v)).g;
    EXPECT_GE(grey, previous) << v;
    EXPECT_LE(grey, 1.f) << v;
    previous = grey;
    // One channel rising, the others fixed: that channel never falls.
    EXPECT_GE(tone_map_khr_neutral(vec3(v * 1.05f + 0.001f, 0.3f, 0.2f)).r, tone_map_khr_neutral(vec3(v, 0.3f, 0.2f)).r)
        << v;
  }
}

TEST(ToneMap, AcesFitOfHill) {
  // Grey stays grey (every matrix row sums to 1): 0.108 boosted by 1/0.6 to
  // 0.18, then (a (a + 0.0245786) - 0.000090537) / (a (0.983729 a + 0.432951) + 0.238081).
  expect_near(tone_map_aces(vec3(0.108f)), vec3(0.1055912f));
  expect_near(tone_map_aces(vec3(1.f)), vec3(0.7633974f));
  // Black is clamped to 0 (the fit is slightly negative at 0).
  expect_near(tone_map_aces(vec3(0.f)), vec3(0.f));
}

TEST(ToneMap, AcesIsMonotonicAndBounded) {
  float previous = -1.f;
  for (float v = 0.f; v < 1000.f; v = v * 1.05f + 0.001f) {
    const vec3 c = tone_map_aces(vec3(v));
    EXPECT_GE(c.g, previous) << v;
    previous = c.g;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(c[k], 0.f) << v;
      EXPECT_LE(c[k], 1.f) << v;
    }
    const vec3 coloured = tone_map_aces(vec3(v, 0.5f * v, 0.1f));
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(coloured[k], 0.f) << v;
      EXPECT_LE(coloured[k], 1.f) << v;
    }
  }
}

TEST(ToneMap, OutOfDomainInput) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (ToneMap m : {ToneMap::khr_neutral, ToneMap::aces}) {
    expect_near(apply_tone_map(m, vec3(-1.f, nan, 0.f)), vec3(0.f));
    const vec3 white = apply_tone_map(m, vec3(inf));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(white[k], 1.f, tolerance) << tone_map_name(m);
  }
  EXPECT_EQ(apply_tone_map(ToneMap::none, vec3(2.f, -1.f, 0.5f)), vec3(2.f, -1.f, 0.5f));
}

TEST(ToneMap, Names) {
  for (ToneMap m : {ToneMap::none, ToneMap::khr_neutral, ToneMap::aces})
    EXPECT_EQ(tone_map_from_name(tone_map_name(m)), m);
  EXPECT_EQ(tone_map_name(ToneMap::khr_neutral), std::string("khr-neutral"));
  EXPECT_FALSE(tone_map_from_name("khr_neutral").has_value());
}

}  // namespace
}  // namespace rayform
