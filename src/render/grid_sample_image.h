// The sample image of the course's 3x3-sample grid (grid_filter.h): 3W x 3H
// samples, each its colour, its coverage (1 on a hit, 0 on a miss, for the background and
// coverage) and, with coverage, its colour when it hit (0 when it missed);
// and each pixel filtered from the 7 x 7 samples around its block.
#pragma once

#include "rayform/render/grid_filter.h"

#include <cstddef>
#include <vector>

namespace rayform {

class GridSampleImage {
 public:
  // The sums of a pixel's filtered samples: colour (0-2), coverage (3) and,
  // with coverage, the colour of the samples that hit (4-6).
  static constexpr int max_channels = 7;

  GridSampleImage(int width, int height, bool gaussian, bool hit_colors)
      : width_(width),
        height_(height),
        channels_(hit_colors ? 7 : 4),
        row_(size_t(grid_samples) * size_t(width)),
        samples_(row_ * size_t(grid_samples) * size_t(height) * size_t(channels_)),
        wx_(grid_axis_weights(width, gaussian)),
        wy_(grid_axis_weights(height, gaussian)) {}

  // Sample (a, b) of pixel (x, y) (a, b = 0..2 from the left and the top).
  [[gnu::always_inline]] void set(int x, int y, int a, int b, vec3 c, float coverage, vec3 covered) {
    float* out = samples_.data() + ((size_t(grid_samples) * size_t(y) + size_t(b)) * row_ +
                                    size_t(grid_samples) * size_t(x) + size_t(a)) *
                                       size_t(channels_);
    for (int k = 0; k < 3; ++k) out[k] = c[k];
    out[3] = coverage;
    if (channels_ == 7)
      for (int k = 0; k < 3; ++k) out[4 + k] = covered[k];
  }

  // Pixel (x, y)'s weighted sums over the samples around its block (the
  // weights sum to 1), into sums[0 .. max_channels) (zero before).
  [[gnu::always_inline]] void filter(int x, int y, float* sums) const {
    if (channels_ == 7) filter_channels<7>(x, y, sums);
    else filter_channels<4>(x, y, sums);
  }

 private:
  template <int Channels>
  [[gnu::always_inline]] void filter_channels(int x, int y, float* sums) const {
    const int sample_w = grid_samples * width_, sample_h = grid_samples * height_;
    for (int ky = 0; ky < 7; ++ky) {
      const int sy = grid_samples * y - 2 + ky;
      const float wy = wy_[size_t(y)][size_t(ky)];
      if (sy < 0 || sy >= sample_h || wy == 0.f) continue;
      for (int kx = 0; kx < 7; ++kx) {
        const int sx = grid_samples * x - 2 + kx;
        const float w = wy * wx_[size_t(x)][size_t(kx)];
        if (sx < 0 || sx >= sample_w || w == 0.f) continue;
        const float* in = samples_.data() + (size_t(sy) * row_ + size_t(sx)) * size_t(Channels);
        for (int k = 0; k < Channels; ++k) sums[k] += w * in[k];
      }
    }
  }

  int width_, height_, channels_;
  size_t row_;                  // samples per row of the sample image
  std::vector<float> samples_;  // channels_ floats per sample, rows from the top
  std::vector<GridAxisWeights> wx_, wy_;
};

}  // namespace rayform
