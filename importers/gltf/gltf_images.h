// Images of glTF files, kept by tinygltf's image-loader callback and decoded
// after the load, in parallel, from memory by the core's image_decode.h, never by tinygltf's stb_image:
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
  // The encoded bytes of the images gltf_load_image keeps for
  // decode_gltf_images (tinygltf calls it one image at a time).
  struct Encoded {
    int index = -1;  // into Model::images
    std::vector<unsigned char> bytes;
  };
  std::vector<Encoded> encoded;
};

// tinygltf::LoadImageDataFunction: checks the image's bufferView range and
// keeps its bytes (GltfImageContext::encoded); decode_gltf_images decodes them.
bool gltf_load_image(tinygltf::Image* image, int image_index, std::string* err, std::string* warn, int req_width,
                     int req_height, const unsigned char* bytes, int size, void* user);

// Decodes the images gltf_load_image kept into `model`'s images, in
// parallel; their warnings are added to ctx.warnings in image order.
void decode_gltf_images(GltfImageContext& ctx, tinygltf::Model& model);

// Whether `bytes` start like a KTX2 file.
bool is_ktx2(const unsigned char* bytes, size_t size);

}  // namespace rayform
