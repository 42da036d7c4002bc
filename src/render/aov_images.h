// Turning the per-pixel depth and normal outputs into pictures, with the
// conventions of the course dialects.
#pragma once

#include "rayform/render/render.h"

namespace rayform {

enum class DepthStyle {
  near_white,  // 2012: 1 if t < min, 0 if t > max, else (max - t)/(max - min); miss 0
  near_black,  // 2019: (t - min)/(max - min) clamped to [0, 1]; miss 0
};
enum class NormalStyle {
  absolute,  // 2012: (|x|, |y|, |z|); miss black
  offset,    // 2019: (n + 1)/2; miss 0.5 grey
};

Image depth_image(const RenderResult& r, float min_depth, float max_depth, DepthStyle style);
Image normals_image(const RenderResult& r, NormalStyle style);

// The colour with the coverage as a fourth (alpha) channel, for a render
// with RenderOptions::alpha set: r.color (linear_float) as floats, r.color8
// (unit8, srgb8) as bytes with alpha quantize_unit(coverage).
Image color_with_alpha(const RenderResult& r);
Image8 color8_with_alpha(const RenderResult& r);

}  // namespace rayform
