// Texture lookups on decoded float images (linear RGBA, row 0 = top).
#pragma once

#include "image/image.h"
#include "scene/scene.h"

namespace rayform {

struct TextureImage {
  Image image;  // 4 channels, linear
  Texture::Wrap wrap_u = Texture::Wrap::repeat, wrap_v = Texture::Wrap::repeat;
  Texture::Filter filter = Texture::Filter::linear;
  Texture::Lookup lookup = Texture::Lookup::standard;
};

// Decodes a scene texture to linear RGBA float (sRGB-decoded when srgb is set).
// Throws rayform::Error when the file cannot be read.
TextureImage decode_texture(const Texture& texture);

// RGBA at texture coordinate uv (v = 1 is the top row of the picture).
vec4 sample_texture(const TextureImage& t, vec2 uv);

}  // namespace rayform
