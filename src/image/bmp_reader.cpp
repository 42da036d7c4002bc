// Our reader of the BMP files the course uses: uncompressed 24-bit and 32-bit
// (BI_RGB, or BI_BITFIELDS with the standard byte masks) under a 40, 56, 108
// or 124-byte info header. It exists because OpenImageIO, the reader of every
// other BMP (RLE, paletted, 16-bit, OS/2), costs a process ~0.4 s to load,
// forty times a course render. Strict: the header is read field by field
// within the file's length, the texel limit is checked, then the pixel rows
// are checked to lie inside the file, and only then is memory allocated.
// Values are stb_image's: RGB from 24-bit, RGB or RGBA from 32-bit (BI_RGB
// with an all-zero alpha channel reads as opaque), rows top first.
#include "rayform/image/image_decoders.h"

#include <climits>

namespace rayform {

namespace {

uint32_t u16le(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8; }
uint32_t u32le(const uint8_t* p) { return u16le(p) | u16le(p + 2) << 16; }

constexpr size_t file_header = 14;

struct BmpLayout {
  uint32_t pixel_offset = 0, header_size = 0, compression = 0, bits = 0;
  int64_t width = 0, height = 0;  // height < 0: rows stored top first
  uint32_t alpha_mask = 0;
};

// The header fields of a BMP this reader takes; false for any other file.
bool simple_bmp_layout(const uint8_t* b, size_t size, BmpLayout* l) {
  if (size < file_header + 40 || b[0] != 'B' || b[1] != 'M') return false;
  l->pixel_offset = u32le(b + 10);
  l->header_size = u32le(b + 14);
  const uint32_t hs = l->header_size;
  if (hs != 40 && hs != 56 && hs != 108 && hs != 124) return false;
  if (size < file_header + hs) return false;
  l->width = int32_t(u32le(b + 18));
  l->height = int32_t(u32le(b + 22));
  l->bits = u16le(b + 28);
  l->compression = u32le(b + 30);
  if (l->compression == 0) {  // BI_RGB
    if (l->bits == 24) return true;
    if (l->bits != 32) return false;
    l->alpha_mask = 0xff000000u;  // BGRA (stb's default masks)
    return true;
  }
  if (l->compression != 3 || l->bits != 32 || hs == 56) return false;  // BI_BITFIELDS, 32-bit only
  // The masks follow a 40-byte header (three of them), or lie inside a V4/V5 one.
  const size_t masks = file_header + 40;
  if (size < masks + 12) return false;
  if (u32le(b + masks) != 0x00ff0000u || u32le(b + masks + 4) != 0x0000ff00u || u32le(b + masks + 8) != 0x000000ffu)
    return false;
  if (hs >= 108) {
    l->alpha_mask = u32le(b + masks + 12);
    if (l->alpha_mask != 0 && l->alpha_mask != 0xff000000u) return false;
  }
  return true;
}

}  // namespace

bool is_simple_bmp(const uint8_t* bytes, size_t size) {
  BmpLayout l;
  return simple_bmp_layout(bytes, size, &l);
}

uint64_t simple_bmp_bytes(const uint8_t* bytes, size_t size) {
  BmpLayout l;
  if (!simple_bmp_layout(bytes, size, &l) || l.width <= 0) return 0;
  const uint64_t rows = uint64_t(l.height < 0 ? -l.height : l.height);
  return l.pixel_offset + (uint64_t(l.width) * (l.bits / 8) + 3) / 4 * 4 * rows;
}

DecodeResult decode_bmp(const uint8_t* b, size_t size, const DecodeOptions& options, DecodedImage* out,
                        std::string* error) {
  BmpLayout l;
  if (!simple_bmp_layout(b, size, &l)) {
    *error = "not an uncompressed 24/32-bit BMP";
    return DecodeResult::corrupt;
  }
  if (u16le(b + 26) != 1) {
    *error = "bad BMP header (planes)";
    return DecodeResult::corrupt;
  }
  const uint64_t rows = uint64_t(l.height < 0 ? -l.height : l.height);
  if (l.width <= 0 || rows == 0 || rows > uint64_t(INT_MAX)) {
    *error = "bad BMP dimensions " + std::to_string(l.width) + "x" + std::to_string(l.height);
    return DecodeResult::corrupt;
  }
  const uint64_t width = uint64_t(l.width);
  out->width = int(width);
  out->height = int(rows);
  out->bits = 8;
  out->channels = l.alpha_mask ? 4 : 3;
  if (exceeds_texel_limit(width, rows, options)) return DecodeResult::too_large;
  const uint64_t in_texel = l.bits / 8;
  const uint64_t stride = (width * in_texel + 3) / 4 * 4;  // rows padded to 4 bytes
  const uint64_t header_end = file_header + l.header_size + (l.compression == 3 && l.header_size == 40 ? 12 : 0);
  if (l.pixel_offset < header_end || l.pixel_offset > size) {
    *error = "bad BMP header (pixel data offset " + std::to_string(l.pixel_offset) + ")";
    return DecodeResult::corrupt;
  }
  if (stride > (size - l.pixel_offset) / rows) {  // (divided: no product can wrap)
    *error = "the file is truncated (" + std::to_string(width) + "x" + std::to_string(rows) + " at " +
             std::to_string(l.bits) + " bits needs " + std::to_string(stride) + " bytes a row for " +
             std::to_string(rows) + " rows, the file has " + std::to_string(size - l.pixel_offset) + ")";
    return DecodeResult::corrupt;
  }
  const size_t c = size_t(out->channels);
  if (!charge_decode(width * rows * c, options, out, error)) return DecodeResult::over_budget;
  out->bytes.resize(size_t(width) * rows * c);
  uint8_t alpha_seen = 0;
  for (uint64_t y = 0; y < rows; ++y) {
    const uint64_t file_row = l.height < 0 ? y : rows - 1 - y;
    const uint8_t* src = b + l.pixel_offset + file_row * stride;
    uint8_t* dst = out->bytes.data() + y * width * c;
    for (uint64_t x = 0; x < width; ++x, src += in_texel, dst += c) {
      dst[0] = src[2];
      dst[1] = src[1];
      dst[2] = src[0];
      if (c == 4) alpha_seen |= dst[3] = src[3];
    }
  }
  if (c == 4 && l.compression == 0 && alpha_seen == 0)  // stb: BI_RGB alpha all zero means unused
    for (size_t i = 3; i < out->bytes.size(); i += 4) out->bytes[i] = 255;
  return DecodeResult::ok;
}

}  // namespace rayform
