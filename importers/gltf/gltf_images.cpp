#include "gltf/gltf_images.h"

#include "gltf/gltf_accessors.h"
#include "gltf/gltf_messages.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>
#include <webp/decode.h>

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

// WebP through libwebp, as RGBA8. False (with a reason) when it does not decode.
bool decode_webp(tinygltf::Image* image, const unsigned char* bytes, size_t size, std::string* why) {
  int width = 0, height = 0;
  if (!WebPGetInfo(bytes, size, &width, &height) || width <= 0 || height <= 0) {
    *why = "not a valid WebP stream";
    return false;
  }
  struct Free {
    void operator()(uint8_t* p) const { WebPFree(p); }
  };
  std::unique_ptr<uint8_t, Free> pixels(WebPDecodeRGBA(bytes, size, &width, &height));
  if (!pixels) {
    *why = "the WebP data is corrupt or truncated";
    return false;
  }
  image->width = width;
  image->height = height;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(pixels.get(), pixels.get() + size_t(width) * size_t(height) * 4);
  return true;
}

void mark_undecoded(tinygltf::Image* image) {
  image->image.clear();
  image->width = image->height = -1;
}

}  // namespace

bool is_webp(const unsigned char* bytes, size_t size) {
  return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

bool is_ktx2(const unsigned char* bytes, size_t size) {
  static const unsigned char magic[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  return size >= sizeof magic && std::memcmp(bytes, magic, sizeof magic) == 0;
}

bool gltf_load_image(tinygltf::Image* image, const int image_index, std::string* err, std::string* warn, int, int,
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
  if (is_webp(bytes, length)) {
    std::string why;
    if (!decode_webp(image, bytes, length, &why)) {
      ctx->warnings.push_back(image_name(*image, image_index) + ": cannot decode (" + why +
                              "); textures using it are dropped");
      mark_undecoded(image);
    }
    return true;
  }
  std::string e, w;
  if (!tinygltf::LoadImageData(image, image_index, &e, &w, 0, 0, bytes, size, nullptr)) {
    ctx->warnings.push_back(image_name(*image, image_index) + ": cannot decode (" + gltf_one_line(e) +
                            "); textures using it are dropped");
    mark_undecoded(image);
    return true;
  }
  if (warn && !w.empty()) *warn += w;
  if (image->bits == 16) {  // keep the high byte: the Scene holds 8-bit texels
    std::vector<unsigned char> eight(image->image.size() / 2);
    for (size_t i = 0; i < eight.size(); ++i) {
      uint16_t v;
      std::memcpy(&v, &image->image[2 * i], 2);
      eight[i] = static_cast<unsigned char>(v >> 8);
    }
    image->image = std::move(eight);
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  }
  return true;
}

}  // namespace rayform
