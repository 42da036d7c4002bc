// Pixel sampling for anti-aliasing: stratified jittered sub-pixel positions
// with a deterministic per-pixel random sequence (so images do not depend on
// the thread count), independent uniform positions (for comparison), the
// progressive sequence adaptive sampling draws in rounds, and the
// reconstruction filters that weight them.
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

// Where a pixel's samples lie (RenderOptions::sampler).
enum class PixelSampler : uint8_t {
  stratified,  // a stratified point set, jittered per pixel (the default)
  random,      // independent uniform positions in the pixel (no stratification)
};

// Counter-based hash to [0, 1): the same (pixel, sample, dim) always gives the same number.
inline float sample_random(uint32_t pixel, uint32_t sample, uint32_t dim) {
  return hash_to_unit(pixel * 0x9E3779B9u ^ (sample + 0x7F4A7C15u) * 0x85EBCA6Bu ^ (dim + 1u) * 0xC2B2AE35u);
}

struct PixelSampleOffset {
  vec2 offset;  // from the pixel centre, in pixels
  float weight;
};

// The 32 bits of i in reverse order.
inline uint32_t reverse_bits32(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  return ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
}

// Van der Corput radical inverse in base 2 (its 24 leading bits).
inline float radical_inverse2(uint32_t i) { return float(reverse_bits32(i) >> 8) * (1.f / 16777216.f); }

// A point u in the unit square as a filter's offset and weight.
inline PixelSampleOffset filter_offset(vec2 u, PixelFilter filter) {
  if (filter == PixelFilter::box) return {u - 0.5f, 1.f};
  // Tent over [-1, 1]^2, weighted by the filter value.
  vec2 o = 2.f * u - 1.f;
  return {o, (1.f - std::abs(o.x)) * (1.f - std::abs(o.y))};
}

// Sample `index` of independent uniform points in the unit square (dimensions
// 2 and 3 of the pixel's random sequence: not those of the stratified shift).
inline vec2 random_pixel_point(uint32_t pixel, uint32_t index) {
  return vec2(sample_random(pixel, index, 2), sample_random(pixel, index, 3));
}

// Sample `index` of `count` for one pixel: the Hammersley point set
// ((i + 1/2)/N, radical_inverse(i)), well stratified for any N, shifted by a
// per-pixel random offset (Cranley-Patterson rotation) so that neighbouring
// pixels do not share a pattern. A single sample is the pixel centre itself
// (the course's one ray per pixel). With PixelSampler::random, independent
// uniform points instead (a single sample too).
inline PixelSampleOffset pixel_sample(uint32_t pixel, int index, int count, PixelFilter filter,
                                      PixelSampler sampler = PixelSampler::stratified) {
  if (sampler == PixelSampler::random) return filter_offset(random_pixel_point(pixel, uint32_t(index)), filter);
  if (count <= 1) return {vec2(0.f), 1.f};
  vec2 u((float(index) + 0.5f) / float(count), radical_inverse2(uint32_t(index)));
  u += vec2(sample_random(pixel, 0, 0), sample_random(pixel, 0, 1));
  u -= glm::floor(u);
  return filter_offset(u, filter);
}

// The second dimension of the Sobol sequence as 32 fixed-point bits (its
// first is the bit-reversed index). Together they form a (0,2)-sequence:
// every run of 2^k points starting at a multiple of 2^k has exactly one point
// in each elementary interval of area 2^-k (e.g. each cell of a 4x4 grid for
// 16 points).
inline uint32_t sobol2_bits(uint32_t i) {
  uint32_t r = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) r ^= v;
  return r;
}

// Sample `index` of an unbounded stratified sequence for one pixel, for
// sampling in rounds (adaptive sampling): the (0,2)-sequence above, each
// coordinate XOR-scrambled by per-pixel random bits (which keeps every
// round of 2^k points stratified and decorrelates neighbouring pixels).
inline vec2 progressive_pixel_point(uint32_t pixel, uint32_t index) {
  const uint32_t sx = hash_bits(pixel * 0x9E3779B9u ^ 0x68E31DA4u), sy = hash_bits(pixel * 0x85EBCA6Bu ^ 0xB5297A4Du);
  const uint32_t x = reverse_bits32(index) ^ sx, y = sobol2_bits(index) ^ sy;
  return vec2(float(x >> 8), float(y >> 8)) * (1.f / 16777216.f);
}

}  // namespace rayform
