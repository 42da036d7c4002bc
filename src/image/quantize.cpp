#include "rayform/image/quantize.h"

#include "rayform/image/color.h"

#include <bit>
#include <cmath>
#include <limits>

namespace rayform {

uint8_t quantize_srgb_direct(float linear) {
  if (std::isnan(linear)) return 0;
  return quantize_unit(linear_to_srgb(std::clamp(linear, 0.f, 1.f)));
}

namespace {
SrgbQuantizer make_srgb_quantizer() {
  SrgbQuantizer q;
  q.threshold[0] = -std::numeric_limits<float>::infinity();
  // Non-negative floats are ordered as their bit patterns.
  const uint32_t zero = std::bit_cast<uint32_t>(0.f), one = std::bit_cast<uint32_t>(1.f);
  for (int k = 1; k < 256; ++k) {
    if (quantize_srgb_direct(1.f) < k) {
      q.threshold[size_t(k)] = std::numeric_limits<float>::quiet_NaN();  // compares false: never reached
      continue;
    }
    uint32_t lo = zero, hi = one;  // the answer lies in [lo, hi]
    while (lo < hi) {
      uint32_t mid = lo + (hi - lo) / 2;
      if (quantize_srgb_direct(std::bit_cast<float>(mid)) >= k) hi = mid;
      else lo = mid + 1;
    }
    q.threshold[size_t(k)] = std::bit_cast<float>(lo);
  }
  q.threshold[256] = std::numeric_limits<float>::quiet_NaN();
  // Each bucket's level by the (branchy, exact) search over the thresholds.
  for (size_t b = 0; b < SrgbQuantizer::buckets; ++b) {
    const float v = std::bit_cast<float>(uint32_t(b) << SrgbQuantizer::bucket_shift);
    int k = 0;
    while (k < 255 && q.threshold[size_t(k + 1)] <= v) ++k;
    q.bucket_level[b] = uint8_t(k);
  }
  q.level_at_or_below_zero = quantize_srgb_direct(0.f);
  q.level_at_or_above_one = quantize_srgb_direct(1.f);
  return q;
}
}  // namespace

const SrgbQuantizer& srgb_quantizer() {
  static const SrgbQuantizer q = make_srgb_quantizer();
  return q;
}

float linear_from_display(float v) {
  const uint8_t wanted = quantize_unit(v);
  float linear = srgb_to_linear(v);
  for (int step = 0; step < 64 && quantize_srgb_direct(linear) != wanted; ++step)
    linear = std::nextafter(linear, quantize_srgb_direct(linear) < wanted ? 2.f : -1.f);
  return linear;
}

}  // namespace rayform
