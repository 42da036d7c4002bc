// Ken Perlin's improved noise (src/math/perlin_noise.h) against the reference
// algorithm's known values, and the course's noise weight built on it.
#include "rayform/math/perlin_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rayform {
namespace {

TEST(PerlinNoise, TheReferencePermutation) {
  // A permutation of 0..255 starting as Perlin's table does.
  std::array<int, 256> seen{};
  for (uint8_t v : perlin_permutation) ++seen[v];
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  EXPECT_EQ(perlin_permutation[0], 151);
  EXPECT_EQ(perlin_permutation[1], 160);
  EXPECT_EQ(perlin_permutation[255], 180);
}

TEST(PerlinNoise, ZeroAtLatticePoints) {
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) EXPECT_EQ(perlin_noise(x, y, z), 0.0) << x << " " << y << " " << z;
  EXPECT_EQ(perlin_noise(255, 256, 1000), 0.0);
}

TEST(PerlinNoise, KnownValues) {
  // The value quoted for Perlin's Java reference, ImprovedNoise.noise(3.14, 42, 7).
  EXPECT_DOUBLE_EQ(perlin_noise(3.14, 42, 7), 0.13691995878400012);
  // At the cell centre every fade is 1/2: the mean of the eight corner
  // gradients dotted with (+-1/2, +-1/2, +-1/2), by hand from the table: -1/4.
  EXPECT_DOUBLE_EQ(perlin_noise(0.5, 0.5, 0.5), -0.25);
  // Half-way along the edge from (0,0,0) to (1,0,0): the corner gradients
  // (hashes 4 and 6 of the table: x + z and x - z) give 1/2 and -1/2, the
  // fade 1/2 averages them: 0.
  EXPECT_EQ(perlin_noise(0.5, 0, 0), 0.0);
  EXPECT_NE(perlin_noise(0.3, 0.7, 0.2), 0.0);
}

TEST(PerlinNoise, PeriodicAndBounded) {
  double lo = 0, hi = 0;
  uint64_t s = 12345;
  auto next = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) * 0x1p-53 * 40.0 - 20.0;
  };
  for (int i = 0; i < 20000; ++i) {
    const double x = next(), y = next(), z = next();
    const double n = perlin_noise(x, y, z);
    ASSERT_TRUE(std::isfinite(n));
    lo = std::min(lo, n);
    hi = std::max(hi, n);
    EXPECT_NEAR(perlin_noise(x + 256, y - 512, z + 256), n, 1e-9);
  }
  EXPECT_GE(lo, -1.0);
  EXPECT_LE(hi, 1.0);
  EXPECT_LT(lo, -0.5) << "the noise spans a good part of its range";
  EXPECT_GT(hi, 0.5);
}

TEST(PerlinNoise, CourseWeight) {
  // Octaves 0: the plain sine stripes w = (sin(f x) + 1) / 2.
  EXPECT_NEAR(course_noise_weight(vec3(0.25f, 3.f, 4.f), 0, 2.f, 4.f), (std::sin(0.5) + 1) / 2, 1e-7);
  // At a lattice point every octave is 0.
  EXPECT_EQ(course_noise_weight(vec3(0.f), 5, 8.f, 4.f), 0.5f);
  // Octaves add noise(2^i p) / 2^i.
  const vec3 p(0.3f, 0.7f, 0.2f);
  const double sum = perlin_noise(p.x, p.y, p.z) + perlin_noise(2.0 * p.x, 2.0 * p.y, 2.0 * p.z) / 2;
  EXPECT_NEAR(course_noise_weight(p, 2, 3.f, 1.5f), (std::sin(3.0 * p.x + 1.5 * sum) + 1) / 2, 1e-7);
}

}  // namespace
}  // namespace rayform
