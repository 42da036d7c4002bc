// Texture lookups on decoded images (row 0 = top). Textures from 8-bit files
// keep 4 bytes a texel and decode through a 256-entry table (raw v/255, or
// sRGB to linear), so a 1024^2 face costs 4 MB instead of 16; other sources
// (hdr, 16-bit, exr, ...) are kept as linear float RGBA. Files are decoded by
// image_decode.h under its texture-size limit.
#pragma once

#include "rayform/image/image.h"
#include "rayform/scene/scene.h"

#include <array>
#include <cstdint>

namespace rayform {

struct TextureImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba8;          // 8-bit sources, RGBA
  std::vector<float> rgbaf;            // other sources, linear RGBA
  std::array<float, 256> to_linear{};  // colour channels of rgba8 (alpha: v * (1/255), never sRGB-decoded)
  Texture::Wrap wrap_u = Texture::Wrap::repeat, wrap_v = Texture::Wrap::repeat;
  Texture::Filter filter = Texture::Filter::linear;
  Texture::Lookup lookup = Texture::Lookup::standard;
  MemoryCharge memory;  // rgba8 or rgbaf, charged to DecodeOptions::memory (job_memory()) before allocation

  bool empty() const { return width == 0 || height == 0; }
  vec4 texel(int x, int y) const {
    size_t i = (size_t(y) * width + x) * 4;
    if (!rgba8.empty())
      return vec4(to_linear[rgba8[i]], to_linear[rgba8[i + 1]], to_linear[rgba8[i + 2]], rgba8[i + 3] * (1.f / 255.f));
    return vec4(rgbaf[i], rgbaf[i + 1], rgbaf[i + 2], rgbaf[i + 3]);
  }
  size_t memory_bytes() const { return rgba8.capacity() + rgbaf.capacity() * sizeof(float); }
};

// Decodes a scene texture (sRGB-decoded to linear when srgb is set): the
// Texture's own pixels, or its file through read_image_file (image.h).
// Throws rayform::Error when the file cannot be read or decoded, or declares
// more than options.max_texels texels, or when the texels would pass the
// memory limit (memory_budget.h).
TextureImage decode_texture(const Texture& texture, const DecodeOptions& options = {});

// RGBA at texture coordinate uv (v = 1 is the top row of the picture).
vec4 sample_texture(const TextureImage& t, vec2 uv);

}  // namespace rayform
