#include "rayform/render/texture_sampler.h"

#include "rayform/image/color.h"
#include "rayform/base/error.h"

#include <algorithm>
#include <cmath>

namespace rayform {

namespace {

// Expands 1-4 channels to RGBA (grey to RGB; missing alpha opaque).
template <class T>
void expand_to_rgba(const T* src, int channels, T opaque, T* dst) {
  dst[0] = src[0];
  dst[1] = channels >= 3 ? src[1] : src[0];
  dst[2] = channels >= 3 ? src[2] : src[0];
  dst[3] = channels == 4 ? src[3] : (channels == 2 ? src[1] : opaque);
}

}  // namespace

TextureImage decode_texture(const Texture& texture, const DecodeOptions& options) {
  TextureImage t;
  t.wrap_u = texture.wrap_u;
  t.wrap_v = texture.wrap_v;
  t.filter = texture.filter;
  t.lookup = texture.lookup;
  DecodedImage file;
  MemoryBudget& budget = options.memory ? *options.memory : job_memory();
  auto name = [&] { return texture.path.empty() ? "texture '" + texture.name + "'" : texture.path; };
  auto size_text = [](int w, int h) { return std::to_string(w) + "x" + std::to_string(h); };
  if (texture.pixels.empty()) {
    DecodeOptions kept = options;
    kept.kept_bytes_per_texel = 4;  // RGBA8 at least (float RGBA: 16)
    file = read_image_file(texture.path, kept);
  }
  if (!texture.pixels.empty() || file.bits == 8) {
    for (int v = 0; v < 256; ++v) t.to_linear[v] = texture.srgb ? srgb_to_linear(v / 255.f) : v / 255.f;
    const uint8_t* src = texture.pixels.empty() ? file.bytes.data() : texture.pixels.data();
    int c = texture.pixels.empty() ? file.channels : texture.channels;
    t.width = texture.pixels.empty() ? file.width : texture.width;
    t.height = texture.pixels.empty() ? file.height : texture.height;
    if (c < 1 || c > 4) throw Error(texture.path + ": unsupported number of channels " + std::to_string(c));
    const size_t texels = size_t(t.width) * size_t(t.height);
    t.memory = budget.charge(texels * 4, name() + ": the " + size_text(t.width, t.height) + " texture as RGBA8");
    if (c == 4) {  // already RGBA (glTF images): a copy
      t.rgba8.assign(src, src + texels * 4);
      return t;
    }
    t.rgba8.resize(texels * 4);
    for (size_t i = 0; i < texels; ++i) expand_to_rgba(src + i * c, c, uint8_t(255), &t.rgba8[i * 4]);
    return t;
  }
  int c = file.channels;
  if (c < 1 || c > 4) throw Error(texture.path + ": unsupported number of channels " + std::to_string(c));
  const size_t texels = size_t(file.width) * size_t(file.height);
  MemoryCharge float_copy =
      budget.charge(texels * size_t(c) * sizeof(float),
                    name() + ": the " + size_text(file.width, file.height) + " texture as floats");
  Image src = to_float_image(file);
  file = DecodedImage();
  t.memory = budget.charge(texels * 4 * sizeof(float),
                           name() + ": the " + size_text(src.width, src.height) + " texture as float RGBA");
  t.width = src.width;
  t.height = src.height;
  t.rgbaf.resize(size_t(t.width) * t.height * 4);
  for (size_t i = 0; i < size_t(t.width) * t.height; ++i) {
    float* d = &t.rgbaf[i * 4];
    expand_to_rgba(&src.pixels[i * c], c, 1.f, d);
    if (texture.srgb)
      for (int k = 0; k < 3; ++k) d[k] = srgb_to_linear(d[k]);
  }
  return t;
}

namespace {

int wrap_index(int i, int n, Texture::Wrap w) {
  switch (w) {
    case Texture::Wrap::clamp: return std::clamp(i, 0, n - 1);
    case Texture::Wrap::repeat: {
      int m = i % n;
      return m < 0 ? m + n : m;
    }
    case Texture::Wrap::mirror: {
      int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
  }
  return 0;
}

}  // namespace

vec4 sample_texture(const TextureImage& t, vec2 uv) {
  if (t.empty()) return vec4(1.f);
  const int w = t.width, h = t.height;
  if (t.lookup == Texture::Lookup::course) {
    // Course convention: texel centres on whole numbers, indices clamped.
    float x = uv.x * w, y = (1.f - uv.y) * h;
    if (!std::isfinite(x) || !std::isfinite(y)) return t.texel(0, 0);
    float fx = std::floor(x), fy = std::floor(y);
    float ax = x - fx, ay = y - fy;
    // Clamp in float first: uv far outside [0,1] must not overflow the int cast.
    int ix = int(std::clamp(fx, -1.f, float(w))), iy = int(std::clamp(fy, -1.f, float(h)));
    auto at = [&](int i, int j) { return t.texel(std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1)); };
    return (1 - ax) * (1 - ay) * at(ix, iy) + ax * (1 - ay) * at(ix + 1, iy) + (1 - ax) * ay * at(ix, iy + 1) +
           ax * ay * at(ix + 1, iy + 1);
  }
  float x = uv.x * w - 0.5f, y = (1.f - uv.y) * h - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return t.texel(0, 0);
  // Keep the integer conversion in range; wrapping makes far values equivalent.
  x = std::fmod(x, float(2 * w));
  y = std::fmod(y, float(2 * h));
  if (t.filter == Texture::Filter::nearest) {
    int ix = int(std::floor(x + 0.5f)), iy = int(std::floor(y + 0.5f));
    return t.texel(wrap_index(ix, w, t.wrap_u), wrap_index(iy, h, t.wrap_v));
  }
  float fx = std::floor(x), fy = std::floor(y);
  float ax = x - fx, ay = y - fy;
  int ix = int(fx), iy = int(fy);
  int x0 = wrap_index(ix, w, t.wrap_u), x1 = wrap_index(ix + 1, w, t.wrap_u);
  int y0 = wrap_index(iy, h, t.wrap_v), y1 = wrap_index(iy + 1, h, t.wrap_v);
  return (1 - ax) * (1 - ay) * t.texel(x0, y0) + ax * (1 - ay) * t.texel(x1, y0) + (1 - ax) * ay * t.texel(x0, y1) +
         ax * ay * t.texel(x1, y1);
}

}  // namespace rayform
