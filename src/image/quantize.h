// Float samples to the 8-bit values of integer image files: the one
// quantisation rule, floor(clamp(v, 0, 1) * 255) with NaN as 0 (as the course
// reference quantises), and the same rule after sRGB encoding.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace rayform {

[[gnu::always_inline]] inline uint8_t quantize_unit(float v) {
  v = std::isnan(v) ? 0.f : std::clamp(v, 0.f, 1.f);
  return uint8_t(std::min(255.f, std::floor(v * 255.f)));
}

// quantize_unit(linear_to_srgb(clamp(v, 0, 1))) for a linear value v, without
// evaluating pow and without data-dependent branches: `threshold[k]` is the
// smallest float v in [0, 1] whose value is k or more (NaN for a value never
// reached: no v compares >= NaN), found once by bisection on float bit
// patterns; `bucket_level[b]` is the value at the start of each run of 2^16
// floats (bit patterns b << 16). A bucket spans less than one step (at most
// 0.66 of one, just below 1), so one comparison finishes the lookup. Equal to
// the direct formula for every input (tests check each threshold, its
// neighbours, every bucket and random inputs against it).
struct SrgbQuantizer {
  static constexpr int bucket_shift = 16;
  static constexpr size_t buckets = (0x3f800000u >> bucket_shift) + 1;  // bit patterns of [0, 1]
  std::array<float, 257> threshold{};  // threshold[0] = -infinity, threshold[256] = NaN
  std::array<uint8_t, buckets> bucket_level{};
  uint8_t level_at_or_below_zero = 0, level_at_or_above_one = 0;

  [[gnu::always_inline]] uint8_t operator()(float v) const {
    if (std::isnan(v)) return 0;
    if (v <= 0.f) return level_at_or_below_zero;
    if (v >= 1.f) return level_at_or_above_one;
    const int k = bucket_level[std::bit_cast<uint32_t>(v) >> bucket_shift];
    return uint8_t(k + (threshold[size_t(k + 1)] <= v));
  }
};

// Built on first use (thread-safe; about 8000 pow evaluations and 16 000 lookups).
const SrgbQuantizer& srgb_quantizer();

// The direct formula the quantizer reproduces (for tests and one-off values).
uint8_t quantize_srgb_direct(float linear);

// The linear value that an sRGB-encoded 8-bit output shows as the display
// value v (0..1, as a colour picker gives it) shows unencoded: srgb_to_linear(v),
// moved by the few float steps needed for quantize_srgb_direct of it to be
// quantize_unit(v) (the round trip in float can land one step below).
float linear_from_display(float v);

}  // namespace rayform
