#include "render/texture_sampler.h"

#include "image/color.h"

#include <algorithm>
#include <cmath>

namespace rayform {

TextureImage decode_texture(const Texture& texture) {
  TextureImage t;
  Image src;
  if (!texture.pixels.empty()) {
    src = Image(texture.width, texture.height, texture.channels);
    for (size_t i = 0; i < src.pixels.size(); ++i) src.pixels[i] = texture.pixels[i] / 255.f;
  } else {
    src = read_image(texture.path);
  }
  Image& img = t.image;
  img = Image(src.width, src.height, 4, 1.f);
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) {
      const float* s = src.at(x, y);
      float* d = img.at(x, y);
      int c = src.channels;
      d[0] = s[0];
      d[1] = c >= 3 ? s[1] : s[0];
      d[2] = c >= 3 ? s[2] : s[0];
      d[3] = c == 4 ? s[3] : (c == 2 ? s[1] : 1.f);
      if (texture.srgb)
        for (int k = 0; k < 3; ++k) d[k] = srgb_to_linear(d[k]);
    }
  t.wrap_u = texture.wrap_u;
  t.wrap_v = texture.wrap_v;
  t.filter = texture.filter;
  t.lookup = texture.lookup;
  return t;
}

namespace {

int wrap_index(int i, int n, Texture::Wrap w) {
  switch (w) {
    case Texture::Wrap::clamp: return std::clamp(i, 0, n - 1);
    case Texture::Wrap::repeat: { int m = i % n; return m < 0 ? m + n : m; }
    case Texture::Wrap::mirror: {
      int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
  }
  return 0;
}

vec4 texel(const Image& img, int x, int y) {
  const float* p = img.at(x, y);
  return vec4(p[0], p[1], p[2], p[3]);
}

}  // namespace

vec4 sample_texture(const TextureImage& t, vec2 uv) {
  const Image& img = t.image;
  if (img.empty()) return vec4(1.f);
  int w = img.width, h = img.height;
  if (t.lookup == Texture::Lookup::course) {
    // Course convention: texel centres on whole numbers, indices clamped.
    float x = uv.x * w, y = (1.f - uv.y) * h;
    float fx = std::floor(x), fy = std::floor(y);
    float ax = x - fx, ay = y - fy;
    // Clamp in float first: uv far outside [0,1] must not overflow the int cast.
    int ix = int(std::clamp(fx, -1.f, float(w))), iy = int(std::clamp(fy, -1.f, float(h)));
    auto at = [&](int i, int j) { return texel(img, std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1)); };
    return (1 - ax) * (1 - ay) * at(ix, iy) + ax * (1 - ay) * at(ix + 1, iy) +
           (1 - ax) * ay * at(ix, iy + 1) + ax * ay * at(ix + 1, iy + 1);
  }
  float x = uv.x * w - 0.5f, y = (1.f - uv.y) * h - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return texel(img, 0, 0);
  // Keep the integer conversion in range; wrapping makes far values equivalent.
  x = std::fmod(x, float(2 * w)); y = std::fmod(y, float(2 * h));
  if (t.filter == Texture::Filter::nearest) {
    int ix = int(std::floor(x + 0.5f)), iy = int(std::floor(y + 0.5f));
    return texel(img, wrap_index(ix, w, t.wrap_u), wrap_index(iy, h, t.wrap_v));
  }
  float fx = std::floor(x), fy = std::floor(y);
  float ax = x - fx, ay = y - fy;
  int ix = int(fx), iy = int(fy);
  int x0 = wrap_index(ix, w, t.wrap_u), x1 = wrap_index(ix + 1, w, t.wrap_u);
  int y0 = wrap_index(iy, h, t.wrap_v), y1 = wrap_index(iy + 1, h, t.wrap_v);
  return (1 - ax) * (1 - ay) * texel(img, x0, y0) + ax * (1 - ay) * texel(img, x1, y0) +
         (1 - ax) * ay * texel(img, x0, y1) + ax * ay * texel(img, x1, y1);
}

}  // namespace rayform
