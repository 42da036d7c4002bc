// WebP through libwebp, from memory, as RGBA (opaque files get alpha 255).
// The bitstream header's dimensions (at most 16383 a side) are checked
// against the texel limit before decoding.
#include "rayform/image/image_decoders.h"

#include <webp/decode.h>

#include <cstring>

namespace rayform {

bool is_webp(const uint8_t* bytes, size_t size) {
  return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

DecodeResult decode_webp(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                         std::string* error) {
  int width = 0, height = 0;
  if (!WebPGetInfo(bytes, size, &width, &height) || width <= 0 || height <= 0) {
    *error = "not a valid WebP stream";
    return DecodeResult::corrupt;
  }
  out->width = width;
  out->height = height;
  out->channels = 4;
  out->bits = 8;
  if (exceeds_texel_limit(uint64_t(width), uint64_t(height), options)) return DecodeResult::too_large;
  const size_t stride = size_t(width) * 4;
  out->bytes.resize(stride * size_t(height));
  if (!WebPDecodeRGBAInto(bytes, size, out->bytes.data(), out->bytes.size(), int(stride))) {
    out->bytes.clear();
    *error = "the WebP data is corrupt or truncated";
    return DecodeResult::corrupt;
  }
  return DecodeResult::ok;
}

}  // namespace rayform
