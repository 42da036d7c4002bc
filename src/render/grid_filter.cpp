#include "rayform/render/grid_filter.h"

namespace rayform {

std::vector<GridAxisWeights> grid_axis_weights(int pixels, bool gaussian) {
  const int samples = grid_samples * pixels;
  std::vector<GridAxisWeights> weights(size_t(pixels > 0 ? pixels : 0));
  for (int p = 0; p < pixels; ++p) {
    GridAxisWeights& w = weights[size_t(p)];
    w.fill(0.f);
    for (int a = 0; a < grid_samples; ++a) {
      const int s = grid_samples * p + a;  // the sample whose blurred value is averaged
      if (!gaussian) {
        w[size_t(a + 2)] += 1.f / float(grid_samples);
        continue;
      }
      double inside = 0.0;
      for (int d = -2; d <= 2; ++d)
        if (s + d >= 0 && s + d < samples) inside += grid_gaussian_taps[size_t(d + 2)];
      for (int d = -2; d <= 2; ++d)
        if (s + d >= 0 && s + d < samples)
          w[size_t(a + 2 + d)] += float(double(grid_gaussian_taps[size_t(d + 2)]) / inside / grid_samples);
    }
  }
  return weights;
}

}  // namespace rayform
