// WebP through libwebp, from memory, as RGBA (opaque files get alpha 255).
// The bitstream header's dimensions (at most 16383 a side) are checked
// against the texel limit before decoding.
#include "rayform/image/image_decoders.h"

#include <webp/decode.h>

#include <cstring>

namespace rayform {
namespace {
// Lossy (VP8): every 16x16 macroblock codes its luma and chroma modes, at
// least ~2 bits under the key frame's fixed probabilities; 1 bit is allowed:
// 256 texels in 1/8 byte.
constexpr uint64_t lossy_ratio = 2048;
// Lossless (VP8L) could code a one-colour image in 0 bits a pixel, but no
// encoder does: libwebp's best, a one-colour 16383x16383 image, takes 10 kB,
// 26 000 texels a byte; 2^20 leaves 40 times that.
constexpr uint64_t lossless_ratio = uint64_t(1) << 20;
}  // namespace

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
  // The data must be there: the RIFF chunk within the file, and at most
  // lossy_ratio (lossless_ratio) texels a byte of the file.
  const uint64_t riff = 8 + uint64_t(bytes[4] | bytes[5] << 8 | bytes[6] << 16 | uint32_t(bytes[7]) << 24);
  WebPBitstreamFeatures features;
  if (riff > size || WebPGetFeatures(bytes, size, &features) != VP8_STATUS_OK) {
    *error = riff > size ? "the WebP data is truncated (its RIFF header declares " + std::to_string(riff) +
                               " bytes, there are " + std::to_string(size) + ")"
                         : "not a valid WebP stream";
    return DecodeResult::corrupt;
  }
  const uint64_t texels = uint64_t(width) * uint64_t(height),
                 ratio = features.format == 2 ? lossless_ratio : lossy_ratio;
  if (texels > ratio * size) {
    *error = "the header declares " + std::to_string(width) + "x" + std::to_string(height) + " texels, more than its " +
             std::to_string(size) + " bytes can hold (a " + (features.format == 2 ? "lossless" : "lossy") +
             " WebP holds at most " + std::to_string(ratio) + " texels a byte)";
    return DecodeResult::corrupt;
  }
  const size_t stride = size_t(width) * 4;
  if (!charge_decode(uint64_t(stride) * uint64_t(height), options, out, error)) return DecodeResult::over_budget;
  out->bytes.resize(stride * size_t(height));
  if (!WebPDecodeRGBAInto(bytes, size, out->bytes.data(), out->bytes.size(), int(stride))) {
    out->bytes.clear();
    *error = "the WebP data is corrupt or truncated";
    return DecodeResult::corrupt;
  }
  return DecodeResult::ok;
}

}  // namespace rayform
