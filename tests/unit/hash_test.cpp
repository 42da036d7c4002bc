// Stateless pseudo-random numbers (src/math/hash.h) and the pixel sample
// sequence built on them (src/render/sampling.h).
#include "rayform/math/hash.h"
#include "rayform/render/sampling.h"

#include <gtest/gtest.h>

#include <set>

namespace rayform {
namespace {

TEST(Hash, KnownValuesOfTheFinaliser) {
  // lowbias32 (x ^= x >> 16; x *= 0x7feb352d; x ^= x >> 15; x *= 0x846ca68b;
  // x ^= x >> 16) evaluated with arbitrary-precision integers mod 2^32.
  EXPECT_EQ(hash_bits(0u), 0u);
  EXPECT_EQ(hash_bits(1u), 0x688990c0u);
  EXPECT_EQ(hash_to_unit(0u), 0.f);
  EXPECT_EQ(hash_to_unit(1u), float(0x688990c0u >> 8) / 16777216.f);
}

TEST(Hash, UnitValuesStayBelowOneAndSpreadEvenly) {
  int bins[10] = {};
  const int n = 100000;
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    const float u = hash_to_unit(i);
    ASSERT_GE(u, 0.f);
    ASSERT_LT(u, 1.f);
    ++bins[int(u * 10.f)];
  }
  for (int b : bins) EXPECT_NEAR(b, n / 10, n / 100);  // within 10 % of uniform
}

TEST(Hash, SampleRandomDependsOnEveryArgument) {
  const float base = sample_random(7, 3, 1);
  EXPECT_EQ(sample_random(7, 3, 1), base);  // deterministic
  EXPECT_NE(sample_random(8, 3, 1), base);
  EXPECT_NE(sample_random(7, 4, 1), base);
  EXPECT_NE(sample_random(7, 3, 2), base);
  std::set<float> distinct;
  for (uint32_t p = 0; p < 64; ++p)
    for (uint32_t d = 0; d < 2; ++d) distinct.insert(sample_random(p, 0, d));
  EXPECT_EQ(distinct.size(), 128u);
}

}  // namespace
}  // namespace rayform
