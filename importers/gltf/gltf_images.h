// Images of glTF files, decoded for tinygltf (its image-loader callback)
// from memory by the core's image_decode.h, never by tinygltf's stb_image:
// PNG (libpng), JPEG (libjpeg-turbo), WebP (EXT_texture_webp, libwebp), as
// RGBA8 as tinygltf's loader gave (16-bit images reduced to their high byte:
// the Scene holds 8-bit texels), under the texture-size limit of
// GltfImageContext::decode. KTX2 / Basis Universal (KHR_texture_basisu) has
// no decoder here: such images are left empty, and the reader falls back to
// the texture's PNG/JPEG source or refuses the texture
// (gltf_read_materials.cpp: texture_source). An image that cannot be decoded,
// or is larger than the limit, is a warning, not an error: the asset still
// loads, untextured there.
#pragma once

#include "rayform/image/image_decode.h"

#include <string>
#include <vector>

namespace tinygltf {
struct Image;
class Model;
}  // namespace tinygltf

namespace rayform {

// The user data of gltf_load_image.
struct GltfImageContext {
  const tinygltf::Model* model = nullptr;  // to check bufferView ranges, which tinygltf does not
  std::vector<std::string> warnings;       // "images[2]: cannot decode (...)"
  std::vector<int> ktx2_images;            // images left empty because they are KTX2
  DecodeOptions decode;                    // the texel limit
};

// tinygltf::LoadImageDataFunction.
bool gltf_load_image(tinygltf::Image* image, int image_index, std::string* err, std::string* warn, int req_width,
                     int req_height, const unsigned char* bytes, int size, void* user);

// Whether `bytes` start like a KTX2 file.
bool is_ktx2(const unsigned char* bytes, size_t size);

}  // namespace rayform
