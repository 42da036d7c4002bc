// Pixel sampling beyond a fixed spp: the 2012 assignment 5's 3x3 grid with
// its Gaussian (RenderOptions::grid, render/grid_filter.h) against the filter
// computed here by direct convolution, adaptive sampling
// (RenderOptions::target_error) on a flat picture, a sharp edge and a lit
// sphere against a 4096-spp reference, the random sampler against the
// stratified one, and the independence of all of them from threads and tiles.
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/base/error.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace rayform {
namespace {

constexpr int size = 16;

// Seen by an orthographic camera from +z, pixel centres spanning x, y in
// [-1, 1] (continuous pixel i at x = 2i/15 - 1): an unlit white triangle
// whose right edge is the vertical line x = edge_x, covering everything to its
// left, on a black background. `color` replaces white.
Scene edge_scene(float edge_x, vec3 color = vec3(1.f)) {
  Scene s;
  Camera c;
  c.projection = Camera::Projection::orthographic;
  c.center = vec3(0.f, 0.f, 10.f);
  c.direction = vec3(0.f, 0.f, -1.f);
  c.ortho_height = 2.f;
  s.cameras.push_back(c);
  s.background.color = vec3(0.f);
  Material m;
  m.unlit = true;
  m.diffuse = color;
  s.materials = {m};
  s.triangles = {Triangle{{vec3(edge_x, -1000.f, 0.f), vec3(edge_x, 1000.f, 0.f), vec3(-1000.f, 0.f, 0.f)}}};
  test::add_root_group(s, {test::shape_node(ShapeKind::triangle, 0, 0)});
  return s;
}

Scene sphere_scene() { return test::lit_sphere_scene(vec3(0.1f, 0.2f, 0.3f)); }

RenderOptions options(int width, int height) {
  RenderOptions o;
  o.width = width;
  o.height = height;
  return o;
}

float red(const RenderResult& r, int x, int y) { return r.color.pixels[3 * (size_t(y) * size_t(r.width) + x)]; }

bool same_bits(const RenderResult& a, const RenderResult& b) {
  return a.color.pixels.size() == b.color.pixels.size() &&
         std::memcmp(a.color.pixels.data(), b.color.pixels.data(), a.color.pixels.size() * sizeof(float)) == 0;
}

// The assignment's filter along one row, by direct convolution: `samples`
// values, each blurred with the 5 taps (those outside the row dropped and the
// rest renormalised), then averaged in threes.
std::vector<double> gaussian_then_average(const std::vector<double>& samples) {
  const double taps[5] = {0.1201, 0.2339, 0.2921, 0.2339, 0.1201};
  const int n = int(samples.size());
  std::vector<double> blurred(size_t(n), 0.0);
  for (int s = 0; s < n; ++s) {
    double sum = 0.0, weight = 0.0;
    for (int d = -2; d <= 2; ++d) {
      if (s + d < 0 || s + d >= n) continue;
      sum += taps[d + 2] * samples[size_t(s + d)];
      weight += taps[d + 2];
    }
    blurred[size_t(s)] = sum / weight;
  }
  std::vector<double> pixels(size_t(n / 3));
  for (size_t p = 0; p < pixels.size(); ++p)
    pixels[p] = (blurred[3 * p] + blurred[3 * p + 1] + blurred[3 * p + 2]) / 3.0;
  return pixels;
}

TEST(GridFilter, GaussianOnASharpEdgeMatchesDirectConvolution) {
  // The edge at x = 0 is the border between pixels 7 and 8 (i = 7.5): samples
  // 0..23 of each 48-sample row are white, 24..47 black, jittered or not.
  const Scene scene = edge_scene(0.f);
  const PreparedScene p = prepare_scene(scene);
  std::vector<double> row(3 * size, 0.0);
  for (int s = 0; s < 3 * size / 2; ++s) row[size_t(s)] = 1.0;
  const std::vector<double> expected = gaussian_then_average(row);
  // Hand check of the reference: pixel 7 averages samples 21 (1), 22 (all
  // but the 0.1201 tap) and 23 (the three taps on its left), over 1.0001.
  EXPECT_NEAR(expected[7], (1.0 + (1.0001 - 0.1201) / 1.0001 + (0.1201 + 0.2339 + 0.2921) / 1.0001) / 3.0, 1e-12);
  EXPECT_NEAR(expected[8], 1.0 - expected[7], 1e-12);
  for (bool jitter : {false, true}) {
    RenderOptions o = options(size, size);
    o.grid.gaussian = true;
    o.grid.jitter = jitter;
    const RenderResult r = render(p, o);
    EXPECT_EQ(r.samples, uint64_t(9 * size * size));
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        ASSERT_NEAR(red(r, x, y), expected[size_t(x)], 1e-6) << "pixel " << x << "," << y << " jitter " << jitter;
    EXPECT_GT(red(r, 7, 5), 0.8f);  // pixel 7 gets black from pixel 8's samples
    EXPECT_LT(red(r, 7, 5), 0.85f);
  }
}

TEST(GridFilter, JitterAloneAveragesThePixelsOwnSamples) {
  // Edge through the middle of column 7 (x = 2*7/15 - 1): of its 3x3
  // jittered samples the left column lies left of the edge, the right column
  // right of it, and each of the middle column's three falls on either side.
  // Other pixels are flat.
  const Scene scene = edge_scene(2.f * 7.f / 15.f - 1.f);
  const PreparedScene p = prepare_scene(scene);
  RenderOptions o = options(size, size);
  o.grid.jitter = true;
  const RenderResult r = render(p, o);
  EXPECT_EQ(r.samples, uint64_t(9 * size * size));
  int counts[4] = {};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float v = red(r, x, y);
      if (x < 7) ASSERT_NEAR(v, 1.f, 1e-6f) << x << "," << y;
      else if (x > 7) ASSERT_EQ(v, 0.f) << x << "," << y;
      else {
        // The average of 9 samples of which 3 + m are white, m = 0..3.
        const float m = 9.f * v - 3.f;
        ASSERT_NEAR(m, std::round(m), 1e-5f) << v;
        ASSERT_GE(std::round(m), 0.f);
        ASSERT_LE(std::round(m), 3.f);
        ++counts[int(std::round(m))];
      }
    }
  // 48 middle samples, each left of the edge with probability 1/2: the 16
  // pixels are not all alike.
  EXPECT_LT(std::max({counts[0], counts[1], counts[2], counts[3]}), size);
}

TEST(GridFilter, FlatPictureStaysFlatToTheEdgesAndIndependentOfThreads) {
  // The triangle covers the whole view: the renormalised Gaussian keeps 0.6
  // in the corners too.
  const Scene flat_scene = edge_scene(100.f, vec3(0.6f));
  const PreparedScene flat = prepare_scene(flat_scene);
  RenderOptions o = options(size, 12);
  o.grid.gaussian = true;
  const RenderResult r = render(flat, o);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < size; ++x) ASSERT_NEAR(red(r, x, y), 0.6f, 1e-6f) << x << "," << y;

  const Scene sphere_s = sphere_scene();
  const PreparedScene sphere = prepare_scene(sphere_s);
  RenderOptions a = options(40, 30);
  a.grid.jitter = a.grid.gaussian = true;
  a.threads = 1;
  const RenderResult one = render(sphere, a);
  a.threads = 2;
  a.tile_size = 7;
  EXPECT_TRUE(same_bits(one, render(sphere, a)));
  a.grid.jitter = false;
  EXPECT_FALSE(same_bits(one, render(sphere, a)));  // the jitter changes edge pixels
}

TEST(AdaptiveSampling, FlatPictureTakesOneRoundEdgeColumnTakesTheMost) {
  RenderOptions o = options(size, size);
  o.target_error = 0.01f;
  o.max_spp = 256;
  const Scene flat_scene = edge_scene(100.f, vec3(0.6f));
  const RenderResult flat = render(prepare_scene(flat_scene), o);
  EXPECT_EQ(flat.samples, uint64_t(size * size * adaptive_first_round_samples));
  EXPECT_NEAR(red(flat, 3, 3), 0.6f, 1e-6f);
  // The edge through the middle of column 7: those pixels are half white, a
  // standard deviation of 0.5, so the standard error stays above 0.01 up to
  // 2500 samples: they take all 256; every other pixel is flat and stops
  // after its first round of 4, but columns 6 and 8 take 32 as neighbours
  // of unsettled pixels.
  const Scene edge_s = edge_scene(2.f * 7.f / 15.f - 1.f);
  const PreparedScene edge = prepare_scene(edge_s);
  const RenderResult r = render(edge, o);
  EXPECT_EQ(r.samples, uint64_t((size * size - 3 * size) * 4 + size * 256 + 2 * size * adaptive_neighbour_samples));
  for (int y = 0; y < size; ++y) EXPECT_NEAR(red(r, 7, y), 0.5f, 0.02f) << "row " << y;
  // A looser target: the edge pixels (2 of 4, then 8 of 16 samples white)
  // stop as soon as the standard error of their mean (about 0.5 / sqrt(n))
  // is below 0.1, after 32 samples, as do their neighbours.
  o.target_error = 0.1f;
  const RenderResult loose = render(edge, o);
  EXPECT_EQ(loose.samples, uint64_t((size * size - 3 * size) * 4 + 3 * size * 32));
  // max_spp between the first round and 16: the flat pixels stop at 4, the
  // edge and its neighbours take the 5 allowed; smaller than the first
  // round: exactly that many everywhere.
  o.max_spp = 5;
  EXPECT_EQ(render(edge, o).samples, uint64_t((size * size - 3 * size) * 4 + 3 * size * 5));
  o.max_spp = 3;
  EXPECT_EQ(render(edge, o).samples, uint64_t(size * size * 3));
}

TEST(AdaptiveSampling, PixelsBesideAnEdgeBetweenThemTakeSixteen) {
  // The edge on the border of columns 7 and 8: every pixel is one colour, so
  // all first rounds settle with no variance, but 7 and 8 differ by 1 (more
  // than the target) from a neighbour: they take the first 16 samples (an
  // edge between them could cross one by less than a stratum), the rest 4.
  RenderOptions o = options(size, size);
  o.target_error = 0.01f;
  const Scene s = edge_scene(0.f);
  const RenderResult r = render(prepare_scene(s), o);
  EXPECT_EQ(r.samples, uint64_t((size * size - 2 * size) * adaptive_first_round_samples + 2 * size * 16));
  for (int y = 0; y < size; ++y) {
    EXPECT_EQ(red(r, 7, y), 1.f) << "row " << y;
    EXPECT_EQ(red(r, 8, y), 0.f) << "row " << y;
  }
  // A target above the contrast: no pixel goes on.
  o.target_error = 1.5f;
  EXPECT_EQ(render(prepare_scene(s), o).samples, uint64_t(size * size * adaptive_first_round_samples));
}

TEST(AdaptiveSampling, WithinTheTargetOfA4096SppReference) {
  const Scene scene = sphere_scene();
  const PreparedScene p = prepare_scene(scene);
  RenderOptions ref = options(32, 32);
  ref.spp = 4096;
  const RenderResult reference = render(p, ref);
  for (float target : {0.02f, 0.005f}) {
    RenderOptions o = options(32, 32);
    o.target_error = target;
    o.max_spp = 4096;
    o.threads = 1;
    const RenderResult r = render(p, o);
    double squares = 0.0, worst = 0.0;
    for (size_t k = 0; k < r.color.pixels.size(); ++k) {
      const double d = std::abs(double(r.color.pixels[k]) - double(reference.color.pixels[k]));
      squares += d * d;
      worst = std::max(worst, d);
    }
    const double rmse = std::sqrt(squares / double(r.color.pixels.size()));
    // The standard error bounds the typical error of a pixel; stratified
    // samples do better than independent ones, and flat pixels have none, so
    // RMSE is well below the target (measured: 0.00125 at 0.02, 0.00038 at
    // 0.005; with a first round of 16 it was 0.0013 and 0.00049). A single
    // pixel may be off by a few standard errors where its first rounds missed
    // a feature (measured worst: 0.98 and 1.9 targets); 3 targets for 3072
    // values. The result is deterministic: no flakiness.
    EXPECT_LT(rmse, 0.25 * target) << "target " << target;
    EXPECT_LT(worst, 3.0 * target) << "target " << target;
    // Far fewer samples than the reference (measured: 12.1 and 54.5 per
    // pixel; 18.2 and 61 with a first round of 16), more than the first
    // round on the edges; at 0.02 fewer than 16 per pixel: the flat
    // background and the smooth inside stop after 4.
    EXPECT_GT(r.samples, uint64_t(32 * 32 * adaptive_first_round_samples));
    if (target == 0.02f) {
      EXPECT_LT(r.samples, uint64_t(32 * 32 * adaptive_round_samples));
    }
    EXPECT_LT(r.samples, uint64_t(32 * 32 * 4096 / 32));
    o.threads = 2;
    o.tile_size = 5;
    const RenderResult two = render(p, o);
    EXPECT_TRUE(same_bits(r, two)) << "target " << target;
    EXPECT_EQ(r.samples, two.samples);
  }
}

TEST(AdaptiveSampling, BadValuesAreRefused) {
  RenderOptions o = options(8, 8);
  EXPECT_EQ(render_options_problem(o), "");
  for (float bad : {0.f, -0.5f, std::numeric_limits<float>::quiet_NaN()}) {
    o.target_error = bad;
    EXPECT_EQ(render_options_problem(o).rfind("target-error: must be a positive number", 0), 0u) << bad;
  }
  o.target_error = 0.01f;
  o.filter = PixelFilter::tent;
  EXPECT_EQ(render_options_problem(o), "target-error: adaptive sampling uses the box filter");
  o.filter = PixelFilter::box;
  o.max_spp = 0;
  EXPECT_EQ(render_options_problem(o), "max-spp: must be at least 1, got 0");
  o.max_spp = 1;
  EXPECT_EQ(render_options_problem(o), "");
  o.grid.jitter = true;
  EXPECT_EQ(render_options_problem(o).rfind("target-error: the 3x3 samples", 0), 0u);
  o.target_error.reset();
  o.spp = 4;
  EXPECT_EQ(render_options_problem(o).rfind("spp: the 3x3 samples", 0), 0u);
  o.grid.jitter = false;
  o.target_error = 0.f;
  const Scene scene = sphere_scene();
  EXPECT_THROW(render(prepare_scene(scene), o), Error);
}

TEST(RandomSampler, LessAccurateThanStratifiedAndNotTheCentreAtOneSample) {
  const Scene scene = sphere_scene();
  const PreparedScene p = prepare_scene(scene);
  RenderOptions ref = options(32, 32);
  ref.spp = 4096;
  const RenderResult reference = render(p, ref);
  auto rmse = [&](const RenderResult& r) {
    double squares = 0.0;
    for (size_t k = 0; k < r.color.pixels.size(); ++k) {
      const double d = double(r.color.pixels[k]) - double(reference.color.pixels[k]);
      squares += d * d;
    }
    return std::sqrt(squares / double(r.color.pixels.size()));
  };
  RenderOptions o = options(32, 32);
  o.spp = 64;
  const double stratified = rmse(render(p, o));
  o.sampler = PixelSampler::random;
  const RenderResult random = render(p, o);
  // Independent samples: error ~ n^-1/2 on edges; stratified ~ n^-3/4
  // (measured: 0.0026 against 0.00072).
  EXPECT_GT(rmse(random), 2.5 * stratified);
  o.threads = 1;
  EXPECT_TRUE(same_bits(random, render(p, o)));
  // One random sample per pixel is not the centre ray.
  o.spp = 1;
  const RenderResult one = render(p, o);
  o.sampler = PixelSampler::stratified;
  EXPECT_FALSE(same_bits(one, render(p, o)));
  EXPECT_EQ(one.samples, uint64_t(32 * 32));
}

}  // namespace
}  // namespace rayform
