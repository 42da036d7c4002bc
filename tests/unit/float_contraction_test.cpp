// Floating point is computed as written in every build (CMakeLists.txt:
// -ffp-contract=off): a * b + c is two roundings, never one fused
// multiply-add, even in code compiled for a CPU with FMA. The OBJ polygon
// split must reproduce tinyobjloader's float sums bit for bit, and the
// watertight triangle test needs a * b - c * d to be the exact negative of
// c * d - a * b.
#include <gtest/gtest.h>

namespace {

// Compiled for FMA, as the whole of a -march=x86-64-v3 build is; without
// -ffp-contract=off both GCC (C++ default: fast) and clang (on) fuse this.
__attribute__((target("fma"))) float product_plus(float a, float b, float c) { return a * b + c; }
__attribute__((target("fma"))) float difference_of_products(float a, float b, float c, float d) {
  return a * b - c * d;
}

TEST(FloatContraction, ProductsAreRoundedBeforeTheSum) {
  if (!__builtin_cpu_supports("fma")) GTEST_SKIP() << "this CPU has no FMA";
  // (1 + 2^-12)^2 = 1 + 2^-11 + 2^-24 rounds to 1 + 2^-11 (2^-24 is half an
  // ulp of 1; ties to even), so the sum is 0; fused it would be 2^-24.
  volatile float a = 1.f + 0x1p-12f, c = -(1.f + 0x1p-11f);
  EXPECT_EQ(product_plus(a, a, c), 0.f);
  volatile float one = 1.f;
  // Either order of the same two products gives exact negatives: a * a - 1
  // is the rounded 2^-11 (fused it would be 2^-11 + 2^-24).
  EXPECT_EQ(difference_of_products(a, a, one, one), -difference_of_products(one, one, a, a));
  EXPECT_EQ(difference_of_products(a, a, one, one), 0x1p-11f);
}

}  // namespace
