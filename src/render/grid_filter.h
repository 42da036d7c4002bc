// The anti-aliasing of the course's 2012 assignment 5 (-jitter, -filter):
// every pixel takes 3x3 samples, so the picture is first a 3W x 3H sample
// image; -filter blurs that image with the separable 5-tap Gaussian
// [0.1201 0.2339 0.2921 0.2339 0.1201] (so samples of neighbouring pixels
// contribute), and each pixel is then the average of its 3x3 block. -jitter
// moves each sample to a random point of its third of the pixel (rayform's
// deterministic per-pixel sequence, not the solution's unseeded rand());
// without it the samples are the centres of the thirds.
//
// Weights: the blur and the block average are both separable, so a pixel's
// colour is sum_ky sum_kx wy[ky] wx[kx] S(3x - 2 + kx, 3y - 2 + ky) over the
// 7 x 7 samples around its block, with 7 weights per column and per row
// (grid_axis_weights). Each Gaussian is divided by the sum of its taps inside
// the image (1.0001 in the interior): at the image's edges the taps outside
// are dropped and the rest renormalised, so a flat picture stays flat.
#pragma once

#include "rayform/math/math.h"
#include "rayform/render/sampling.h"

#include <array>
#include <cstdint>
#include <vector>

namespace rayform {

struct GridFilter {
  bool jitter = false;    // -jitter: samples jittered within their thirds of the pixel
  bool gaussian = false;  // -filter: the 5-tap Gaussian over the sample image
  bool on() const { return jitter || gaussian; }
};

inline constexpr int grid_samples = 3;  // per pixel and axis
inline constexpr std::array<float, 5> grid_gaussian_taps = {0.1201f, 0.2339f, 0.2921f, 0.2339f, 0.1201f};

// The 7 weights of pixel `p` (0..pixels-1) along one axis, for samples
// 3p - 2 ... 3p + 4 of that axis (those outside the image weigh 0).
using GridAxisWeights = std::array<float, 7>;
std::vector<GridAxisWeights> grid_axis_weights(int pixels, bool gaussian);

// Where sample (a, b) of pixel `pixel` lies, as an offset from the pixel
// centre in pixels: a = 0..2 from the left, b = 0..2 from the top (so +y of
// the returned offset is down the image).
inline vec2 grid_sample_offset(uint32_t pixel, int a, int b, bool jitter) {
  vec2 u(0.5f);
  if (jitter) {
    const uint32_t n = uint32_t(b * grid_samples + a);
    u = vec2(sample_random(pixel, n, 4), sample_random(pixel, n, 5));
  }
  return (vec2(float(a), float(b)) + u) * (1.f / float(grid_samples)) - 0.5f;
}

}  // namespace rayform
