// The render loop's parts on their own: the tile scheduler renders each tile
// once (every tile, or those a hook hands out), refuses a tile the image does
// not have, and counts progress over all passes; the film's sums give the
// background where every sample missed and AlphaMode's colours; adaptive
// sampling's rounds end where adaptive_sampling.h says.
#include "rayform/render/adaptive_sampling.h"
#include "rayform/render/film.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/tile_scheduler.h"
#include "rayform/base/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <mutex>
#include <vector>

namespace rayform {
namespace {

TEST(TileScheduler, EveryTileOnceAtAnyThreadCount) {
  for (int threads : {0, 1, 3}) {
    std::vector<std::atomic<int>> rendered(37);
    std::vector<float> fractions;
    std::mutex m;
    std::function<void(float)> progress = [&](float f) {
      std::lock_guard lock(m);
      fractions.push_back(f);
    };
    {
      TileScheduler scheduler(37, threads, 2, progress);
      scheduler.every_tile([&](int t) { ++rendered[size_t(t)]; });
      scheduler.tiles_from(nullptr, [&](int t) { ++rendered[size_t(t)]; });
    }
    for (const auto& n : rendered) EXPECT_EQ(n.load(), 2) << threads << " threads";
    ASSERT_EQ(fractions.size(), 74u);
    EXPECT_FLOAT_EQ(*std::max_element(fractions.begin(), fractions.end()), 1.f);
  }
}

TEST(TileScheduler, TilesFromHook) {
  for (int threads : {1, 2}) {
    std::atomic<int> next{0};
    std::vector<std::atomic<int>> rendered(10);
    const NextTile hand_out = [&] {
      const int t = next++;
      return t < 5 ? 2 * t : -1;  // the even tiles
    };
    const std::function<void(float)> no_progress;
    TileScheduler scheduler(10, threads, 1, no_progress);
    scheduler.tiles_from(&hand_out, [&](int t) { ++rendered[size_t(t)]; });
    for (int t = 0; t < 10; ++t) EXPECT_EQ(rendered[size_t(t)].load(), t % 2 ? 0 : 1) << t;
  }
}

TEST(TileScheduler, RefusesATileTheImageLacks) {
  const NextTile too_far = [n = 0]() mutable { return n++ == 0 ? 10 : -1; };
  const std::function<void(float)> no_progress;
  TileScheduler scheduler(10, 1, 1, no_progress);
  EXPECT_THROW(scheduler.tiles_from(&too_far, [](int) {}), Error);
}

TEST(Film, SumsToColourAndCoverage) {
  Scene s;
  s.background.color = vec3(0.25f, 0.5f, 0.75f);
  const PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 2;
  for (AlphaMode mode : {AlphaMode::none, AlphaMode::straight, AlphaMode::premultiplied}) {
    o.alpha = mode;
    RenderResult r = allocate_film(o);
    const Film film(p, o, r);
    PixelValues missed, half;
    film.finish(missed, vec3(0.2f), vec3(0.f), 4.f, 0.f);
    film.finish(half, vec3(2.f, 2.f, 2.f), vec3(1.f, 1.f, 1.f), 4.f, 2.f);
    if (mode == AlphaMode::none) {
      EXPECT_EQ(missed.color, vec3(0.25f, 0.5f, 0.75f));  // the background exactly, not the sums
      EXPECT_EQ(half.color, vec3(0.5f));
    } else if (mode == AlphaMode::straight) {
      EXPECT_EQ(missed.color, vec3(0.25f, 0.5f, 0.75f));
      EXPECT_EQ(half.color, vec3(0.5f));  // over the samples that hit
      EXPECT_EQ(half.coverage, 0.5f);
    } else {
      EXPECT_EQ(missed.color, vec3(0.f));
      EXPECT_EQ(half.color, vec3(0.25f));  // misses count as black
      EXPECT_EQ(half.coverage, 0.5f);
    }
    film.store(3, half);
    EXPECT_EQ(r.color.pixels[9], half.color.x);
    if (mode != AlphaMode::none) {
      EXPECT_EQ(r.coverage[3], 0.5f);
    }
  }
}

TEST(AdaptiveSampling, RoundEnds) {
  EXPECT_EQ(adaptive_round_end(0, 256), 4);
  EXPECT_EQ(adaptive_round_end(4, 256), 16);
  EXPECT_EQ(adaptive_round_end(16, 256), 32);
  EXPECT_EQ(adaptive_round_end(32, 256), 48);
  EXPECT_EQ(adaptive_round_end(4, 10), 10);
  // A flat pixel settles after its first round: no more samples.
  AdaptiveSampler sampler(1, 1, 0.01f, 256, PixelSampler::stratified, false, false);
  int traced = 0;
  auto flat = [&](vec2) {
    ++traced;
    return TracedSample{vec3(0.5f), 1.f, vec3(0.5f)};
  };
  sampler.first_round(0, 0, flat);
  const AdaptiveState st = sampler.complete(0, 0, flat);
  EXPECT_EQ(traced, adaptive_first_round_samples);
  EXPECT_EQ(st.n, adaptive_first_round_samples);
  EXPECT_EQ(st.covered, 4.f);
}

}  // namespace
}  // namespace rayform
