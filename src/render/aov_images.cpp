#include "rayform/render/aov_images.h"

#include "rayform/image/quantize.h"

#include <algorithm>
#include <cmath>

namespace rayform {

Image depth_image(const RenderResult& r, float lo, float hi, DepthStyle style) {
  Image img(r.width, r.height, 3);
  for (size_t i = 0; i < r.depth.size(); ++i) {
    float t = r.depth[i], v = 0.f;
    if (std::isfinite(t)) {
      if (style == DepthStyle::near_white) v = t < lo ? 1.f : (t > hi ? 0.f : (hi - t) / (hi - lo));
      else v = std::clamp((t - lo) / (hi - lo), 0.f, 1.f);
    }
    img.pixels[3 * i] = img.pixels[3 * i + 1] = img.pixels[3 * i + 2] = v;
  }
  return img;
}

Image normals_image(const RenderResult& r, NormalStyle style) {
  Image img(r.width, r.height, 3);
  for (size_t i = 0; i < r.normals.size(); ++i) {
    vec3 n = r.normals[i];
    bool miss = n == vec3(0.f);
    for (int k = 0; k < 3; ++k)
      img.pixels[3 * i + k] = style == NormalStyle::absolute ? std::abs(n[k]) : (miss ? 0.5f : 0.5f * (n[k] + 1.f));
  }
  return img;
}

Image color_with_alpha(const RenderResult& r) {
  Image img(r.width, r.height, 4);
  for (size_t i = 0; i < r.coverage.size(); ++i) {
    for (int k = 0; k < 3; ++k) img.pixels[4 * i + k] = r.color.pixels[3 * i + k];
    img.pixels[4 * i + 3] = r.coverage[i];
  }
  return img;
}

Image8 color8_with_alpha(const RenderResult& r) {
  Image8 img{r.width, r.height, 4, std::vector<unsigned char>(size_t(r.width) * r.height * 4)};
  for (size_t i = 0; i < r.coverage.size(); ++i) {
    for (int k = 0; k < 3; ++k) img.pixels[4 * i + k] = r.color8.pixels[3 * i + k];
    img.pixels[4 * i + 3] = quantize_unit(r.coverage[i]);
  }
  return img;
}

}  // namespace rayform
