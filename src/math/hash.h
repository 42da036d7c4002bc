// Stateless pseudo-random numbers: an integer hash (the "lowbias32" finaliser
// of Chris Wellons' hash-prospector) mapped to a float in [0, 1). The same input
// always gives the same number, so results do not depend on thread count or
// evaluation order.
#pragma once

#include <cstdint>

namespace rayform {

inline uint32_t hash_bits(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// The top 24 bits of hash_bits(x) as a float in [0, 1) (every value exact).
inline float hash_to_unit(uint32_t x) { return float(hash_bits(x) >> 8) * (1.f / 16777216.f); }

}  // namespace rayform
