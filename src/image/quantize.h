// Float samples to the 8-bit values of integer image files: the one
// quantisation rule, floor(clamp(v, 0, 1) * 255) with NaN as 0 (as the course
// reference quantises), and the same rule after sRGB encoding.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace rayform {

inline uint8_t quantize_unit(float v) {
  v = std::isnan(v) ? 0.f : std::clamp(v, 0.f, 1.f);
  return uint8_t(std::min(255.f, std::floor(v * 255.f)));
}

// quantize_unit(linear_to_srgb(clamp(v, 0, 1))) for a linear value v, without
// evaluating pow: `threshold[k]` is the smallest float v in [0, 1] whose value
// is k or more (NaN for a value never reached: no v compares >= NaN), found once by bisection
// on float bit patterns. Equal to the direct formula for every input (tests
// check each threshold, its neighbours and random inputs against it).
struct SrgbQuantizer {
  std::array<float, 256> threshold{};  // threshold[0] = -infinity

  uint8_t operator()(float v) const {
    if (std::isnan(v)) return 0;
    int k = 0;  // the largest k with threshold[k] <= v, in eight steps
    for (int step = 128; step > 0; step >>= 1)
      if (threshold[size_t(k + step)] <= v) k += step;
    return uint8_t(k);
  }
};

// Built on first use (thread-safe; about 8000 pow evaluations).
const SrgbQuantizer& srgb_quantizer();

// The direct formula the quantizer reproduces (for tests and one-off values).
uint8_t quantize_srgb_direct(float linear);

}  // namespace rayform
