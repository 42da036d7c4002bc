#include "image/quantize.h"

#include "image/color.h"

#include <bit>
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
  return q;
}
}  // namespace

const SrgbQuantizer& srgb_quantizer() {
  static const SrgbQuantizer q = make_srgb_quantizer();
  return q;
}

}  // namespace rayform
