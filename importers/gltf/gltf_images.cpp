#include "rayform/importers/gltf/gltf_images.h"

#include "rayform/importers/gltf/gltf_accessors.h"
#include "rayform/importers/gltf/gltf_messages.h"
#include "rayform/base/error.h"
#include "rayform/image/image_decode.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <cstring>
#include <memory>

namespace rayform {

namespace {

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// How a warning names the image: "images[2]" or "images[2] ('wood.png')".
std::string image_name(const tinygltf::Image& image, int index) {
  std::string where = gltf_path("images", index);
  if (!image.uri.empty() && !is_data_uri(image.uri)) where += " ('" + image.uri + "')";
  return where;
}

void mark_undecoded(tinygltf::Image* image) {
  image->image.clear();
  image->width = image->height = -1;
}

// Decodes an image's bytes into it as RGBA8, as tinygltf's loader gave (grey
// repeated, missing alpha opaque; 16-bit samples keep their high byte: the
// Scene holds 8-bit texels). Returns a warning when it cannot ("" when it can).
std::string decode_image(tinygltf::Image& image, int index, const std::vector<unsigned char>& bytes,
                         const DecodeOptions& options) {
  // PNG, JPEG and WebP through image_decode.h (libpng, libjpeg-turbo, libwebp),
  // under the texture-size limit; anything else is undecodable here.
  DecodedImage decoded;
  std::string why;
  const DecodeResult r = decode_image_bytes(bytes.data(), bytes.size(), options, &decoded, &why);
  if (r == DecodeResult::over_budget) throw Error(image_name(image, index) + ": " + why);  // (memory_budget.h)
  if (r != DecodeResult::ok || decoded.bits == 32) {
    if (r == DecodeResult::too_large)
      why = texture_size_message(uint64_t(decoded.width), uint64_t(decoded.height), 4, options);
    else why = "cannot decode (" + (r == DecodeResult::ok ? std::string("not an 8 or 16-bit image") : why) + ")";
    mark_undecoded(&image);
    return image_name(image, index) + ": " + why + "; textures using it are dropped";
  }
  const size_t texels = size_t(decoded.width) * size_t(decoded.height);
  const int c = decoded.channels;
  if (decoded.bits == 8 && c == 4) {
    image.image = std::move(decoded.bytes);
  } else {
    const size_t sample_bytes = decoded.bits / 8;
    auto sample = [&](size_t i, int k) {  // channel k of texel i, 8-bit
      const size_t at = (i * size_t(c) + size_t(k)) * sample_bytes;
      if (sample_bytes == 1) return decoded.bytes[at];
      uint16_t v;
      std::memcpy(&v, &decoded.bytes[at], 2);
      return static_cast<unsigned char>(v >> 8);
    };
    image.image.resize(texels * 4);
    for (size_t i = 0; i < texels; ++i) {
      unsigned char* d = &image.image[i * 4];
      d[0] = sample(i, 0);
      d[1] = sample(i, c >= 3 ? 1 : 0);
      d[2] = sample(i, c >= 3 ? 2 : 0);
      d[3] = c == 4 ? sample(i, 3) : c == 2 ? sample(i, 1) : 255;
    }
  }
  image.width = decoded.width;
  image.height = decoded.height;
  image.component = 4;
  image.bits = 8;
  image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  return "";
}

}  // namespace

bool is_ktx2(const unsigned char* bytes, size_t size) {
  static const unsigned char magic[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  return size >= sizeof magic && std::memcmp(bytes, magic, sizeof magic) == 0;
}

bool gltf_load_image(tinygltf::Image* image, const int image_index, std::string* err, std::string*, int, int,
                     const unsigned char* bytes, int size, void* user) {
  GltfImageContext* ctx = static_cast<GltfImageContext*>(user);
  const std::string where = gltf_path("images", image_index);
  if (image->bufferView >= 0) {
    const tinygltf::Model& m = *ctx->model;
    // tinygltf checked both indices before calling, not the byte range.
    const tinygltf::BufferView& bv = m.bufferViews[size_t(image->bufferView)];
    const tinygltf::Buffer& buf = m.buffers[size_t(bv.buffer)];
    if (!fits_in(bv.byteOffset, bv.byteLength, buf.data.size())) {
      if (err)
        *err += where + ": " + gltf_path("bufferViews", image->bufferView) + " (offset " +
                std::to_string(bv.byteOffset) + ", length " + std::to_string(bv.byteLength) +
                ") lies past the end of " + gltf_path("buffers", bv.buffer) + " (" + std::to_string(buf.data.size()) +
                " bytes)";
      return false;
    }
  }
  if (bytes == nullptr || size <= 0) {
    ctx->warnings.push_back(where + ": no image data; textures using it are dropped");
    return true;
  }
  const size_t length = size_t(size);
  if (is_ktx2(bytes, length)) {  // no KTX2/Basis decoder: the reader decides
    ctx->ktx2_images.push_back(image_index);
    mark_undecoded(image);
    return true;
  }
  ctx->encoded.push_back({image_index, std::vector<unsigned char>(bytes, bytes + length)});
  return true;
}

void decode_gltf_images(GltfImageContext& ctx, tinygltf::Model& model) {
  std::vector<std::string> warnings(ctx.encoded.size());
  tbb::parallel_for(size_t(0), ctx.encoded.size(), [&](size_t j) {
    const GltfImageContext::Encoded& e = ctx.encoded[j];
    warnings[j] = decode_image(model.images[size_t(e.index)], e.index, e.bytes, ctx.decode);
  });
  for (std::string& w : warnings)
    if (!w.empty()) ctx.warnings.push_back(std::move(w));
  ctx.encoded.clear();
}

}  // namespace rayform
