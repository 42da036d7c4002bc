// Pixel sampling for anti-aliasing: stratified jittered sub-pixel positions
// with a deterministic per-pixel random sequence (so images do not depend on
// the thread count), and the reconstruction filters that weight them.
#pragma once

#include "rayform/math/hash.h"
#include "rayform/math/math.h"

#include <cmath>
#include <cstdint>

namespace rayform {

enum class PixelFilter : uint8_t {
  box,   // samples inside the pixel, equal weights
  tent,  // samples within one pixel of the centre, weight (1-|dx|)(1-|dy|)
};

// Counter-based hash to [0, 1): the same (pixel, sample, dim) always gives the same number.
inline float sample_random(uint32_t pixel, uint32_t sample, uint32_t dim) {
  return hash_to_unit(pixel * 0x9E3779B9u ^ (sample + 0x7F4A7C15u) * 0x85EBCA6Bu ^ (dim + 1u) * 0xC2B2AE35u);
}

struct PixelSampleOffset {
  vec2 offset;  // from the pixel centre, in pixels
  float weight;
};

// Van der Corput radical inverse in base 2.
inline float radical_inverse2(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return float(i >> 8) * (1.f / 16777216.f);
}

// Sample `index` of `count` for one pixel: the Hammersley point set
// ((i + 1/2)/N, radical_inverse(i)), well stratified for any N, shifted by a
// per-pixel random offset (Cranley-Patterson rotation) so that neighbouring
// pixels do not share a pattern. A single sample is the pixel centre itself
// (the course's one ray per pixel).
inline PixelSampleOffset pixel_sample(uint32_t pixel, int index, int count, PixelFilter filter) {
  if (count <= 1) return {vec2(0.f), 1.f};
  vec2 u((float(index) + 0.5f) / float(count), radical_inverse2(uint32_t(index)));
  u += vec2(sample_random(pixel, 0, 0), sample_random(pixel, 0, 1));
  u -= glm::floor(u);
  if (filter == PixelFilter::box) return {u - 0.5f, 1.f};
  // Tent over [-1, 1]^2, weighted by the filter value.
  vec2 o = 2.f * u - 1.f;
  return {o, (1.f - std::abs(o.x)) * (1.f - std::abs(o.y))};
}

}  // namespace rayform
