// Adaptive sampling (RenderOptions::target_error): each pixel takes rounds of
// samples until the standard error of its samples' mean, per channel and in
// the output encoding (sRGB-encoded values 0..1 for ColorFormat::srgb8, else
// linear), is below the target, or max_spp samples are taken. A round is a
// run of the pixel's progressive (0,2)-sequence (progressive_pixel_point,
// sampling.h; with PixelSampler::random independent points instead) that
// keeps it stratified: a first round of 4 samples (one in each cell of a 2x2
// grid of the pixel), a second of 12 that completes the first 16 (one in each
// cell of a 4x4 grid), then rounds of 16 (each again one per 4x4 cell); fewer
// when max_spp is smaller. The box filter weights them (equal weights).
//
// A render takes two passes over the tiles: every pixel's first round, kept,
// then the rest. In the second, a pixel whose first round settled goes on
// when its 8 neighbours' first rounds say an edge is near: to
// adaptive_neighbour_samples when a neighbour's did not settle (an edge that
// crosses a corner of a pixel by less than a stratum can escape its first
// samples but not its neighbours'), to the end of its next round when a
// neighbour's mean differs from its own by more than the target (an edge
// between them may cross it unseen). The second pass reads only first-round
// states, so no pixel depends on the order of the tiles.
#pragma once

#include "rayform/image/color.h"
#include "rayform/math/math.h"
#include "rayform/render/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rayform {

inline constexpr int adaptive_first_round_samples = 4;
inline constexpr int adaptive_round_samples = 16;
// The samples a pixel whose first round settled takes when a neighbour's
// first round did not: the first 16 and one round more.
inline constexpr int adaptive_neighbour_samples = 2 * adaptive_round_samples;
// The samples after which a round ends, from the samples taken so far: 4,
// 16, 32, 48, ... (not more than max_spp).
inline constexpr int adaptive_round_end(int taken, int max_spp) {
  const int end = taken < adaptive_first_round_samples ? adaptive_first_round_samples
                  : taken < adaptive_round_samples     ? adaptive_round_samples
                                                       : taken + adaptive_round_samples;
  return end < max_spp ? end : max_spp;
}

// The sums over one pixel's samples so far: all of them, those that hit a
// surface, and the running mean and sum of squared deviations (Welford) of
// their values in the output encoding.
struct AdaptiveState {
  vec3 sum{0.f}, hit_sum{0.f}, mean{0.f}, m2{0.f};
  float covered = 0.f;
  int n = 0;
};

// A traced sample: its colour, the fraction of it surfaces cover (1 on a
// hit, 0 on a miss, between behind blended surfaces) and the part of the
// colour they give (the colour on a hit, 0 on a miss).
struct TracedSample {
  vec3 color;
  float coverage;
  vec3 covered;
};

// Where a pixel's samples go and how many it takes; a caller's `trace(u)`
// traces the sample at point u of the unit square of the pixel.
class AdaptiveSampler {
 public:
  // `srgb`: the output is sRGB-encoded 8-bit (errors are measured encoded);
  // `hit_sums`: keep AdaptiveState::hit_sum (coverage is asked for).
  AdaptiveSampler(int width, int height, float target_error, int max_spp, PixelSampler sampler, bool srgb,
                  bool hit_sums)
      : width_(width),
        height_(height),
        target_error_(target_error),
        target_variance_(target_error * target_error),
        max_spp_(max_spp),
        random_(sampler == PixelSampler::random),
        srgb_(srgb),
        hit_sums_(hit_sums),
        first_rounds_(size_t(width) * size_t(height)) {}

  // The first pass: pixel (x, y)'s first round, kept.
  template <class Trace>
  [[gnu::always_inline]] void first_round(int x, int y, const Trace& trace) {
    const uint32_t pixel = uint32_t(y) * uint32_t(width_) + uint32_t(x);
    round(first_rounds_[pixel], pixel, trace);
  }

  // The second pass: pixel (x, y)'s samples from its first round on.
  template <class Trace>
  [[gnu::always_inline]] AdaptiveState complete(int x, int y, const Trace& trace) const {
    const uint32_t pixel = uint32_t(y) * uint32_t(width_) + uint32_t(x);
    AdaptiveState st = first_rounds_[pixel];
    if (settled(st) && st.n < max_spp_) {
      const int upto = neighbours_ask(x, y, st);
      while (st.n < upto) round(st, pixel, trace);
    }
    while (st.n < max_spp_ && !settled(st)) round(st, pixel, trace);
    return st;
  }

 private:
  // One round of samples (adaptive_round_end) into st.
  template <class Trace>
  [[gnu::always_inline]] void round(AdaptiveState& st, uint32_t pixel, const Trace& trace) const {
    for (const int end = adaptive_round_end(st.n, max_spp_); st.n < end; ++st.n) {
      const vec2 u =
          random_ ? random_pixel_point(pixel, uint32_t(st.n)) : progressive_pixel_point(pixel, uint32_t(st.n));
      const TracedSample s = trace(u);
      const vec3 c = s.color;
      st.sum += c;
      if (s.coverage > 0.f) {
        st.covered += s.coverage;
        if (hit_sums_) st.hit_sum += s.covered;
      }
      vec3 e = c;
      if (srgb_)
        for (int k = 0; k < 3; ++k) e[k] = linear_to_srgb(std::isnan(c[k]) ? 0.f : std::clamp(c[k], 0.f, 1.f));
      const vec3 delta = e - st.mean;
      st.mean += delta / float(st.n + 1);
      st.m2 += delta * (e - st.mean);
    }
  }

  // Whether the squared standard error of the mean, m2 / (n - 1) / n, is below the target's square.
  [[gnu::always_inline]] bool settled(const AdaptiveState& st) const {
    return st.n >= 2 && std::max({st.m2.x, st.m2.y, st.m2.z}) < target_variance_ * float(st.n - 1) * float(st.n);
  }

  // The samples the first rounds of the 8 neighbours of settled pixel (x, y) ask it to take.
  [[gnu::always_inline]] int neighbours_ask(int x, int y, const AdaptiveState& st) const {
    bool neighbour_unsettled = false, neighbour_differs = false;
    for (int ny = std::max(0, y - 1); ny <= std::min(height_ - 1, y + 1); ++ny)
      for (int nx = std::max(0, x - 1); nx <= std::min(width_ - 1, x + 1); ++nx) {
        const AdaptiveState& nb = first_rounds_[size_t(ny) * size_t(width_) + size_t(nx)];
        neighbour_unsettled |= !settled(nb);
        const vec3 d = glm::abs(nb.mean - st.mean);
        neighbour_differs |= std::max({d.x, d.y, d.z}) > target_error_;
      }
    return neighbour_unsettled ? std::min(max_spp_, adaptive_neighbour_samples)
           : neighbour_differs ? adaptive_round_end(st.n, max_spp_)
                               : st.n;
  }

  int width_, height_;
  float target_error_, target_variance_;
  int max_spp_;
  bool random_, srgb_, hit_sums_;
  std::vector<AdaptiveState> first_rounds_;  // every pixel's, from the first pass
};

}  // namespace rayform
