// PNG through libpng (Debian's libpng16), from memory. The header is read
// first and the texel limit checked before any row is decoded. Samples are
// what stb_image gave: palette expanded to RGB (RGBA with a tRNS chunk), grey
// of 1/2/4 bits scaled to 8, tRNS as an alpha channel, 16-bit kept 16-bit; no
// gamma or colour-profile conversion. libpng reports errors by longjmp: the
// function that calls setjmp constructs every object with a destructor before
// it, so the jump skips none.
#include "rayform/image/image_decoders.h"

#include <png.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <vector>

namespace rayform {

namespace {

constexpr uint64_t deflate_max_ratio = 1032;

struct PngSource {
  const uint8_t* bytes;
  size_t size;
  size_t pos;
  char error[200];
};

void png_read_bytes(png_structp png, png_bytep to, size_t length) {
  PngSource* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > src->size - src->pos) png_error(png, "the file is truncated");
  std::memcpy(to, src->bytes + src->pos, length);
  src->pos += length;
}

void png_on_error(png_structp png, png_const_charp message) {
  PngSource* src = static_cast<PngSource*>(png_get_error_ptr(png));
  std::strncpy(src->error, message, sizeof src->error - 1);
  src->error[sizeof src->error - 1] = '\0';
  png_longjmp(png, 1);
}

void png_on_warning(png_structp, png_const_charp) {}  // (bad ancillary chunks are skipped)

uint32_t be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// The bytes of IDAT data (compressed rows) before IEND, the chunks' lengths
// as they lie within `size`.
uint64_t idat_bytes(const uint8_t* bytes, size_t size) {
  uint64_t total = 0;
  for (size_t at = 8; at + 8 <= size;) {
    const uint64_t length = be32(bytes + at);
    if (std::memcmp(bytes + at + 4, "IEND", 4) == 0) break;
    if (std::memcmp(bytes + at + 4, "IDAT", 4) == 0) total += std::min<uint64_t>(length, size - at - 8);
    if (length > size - at - 8) break;
    at += 12 + size_t(length);
  }
  return total;
}

struct PngHandles {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngHandles() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  }
};

}  // namespace

bool is_png(const uint8_t* bytes, size_t size) { return size >= 8 && png_sig_cmp(bytes, 0, 8) == 0; }

DecodeResult decode_png(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                        std::string* error) {
  PngSource src{bytes, size, 0, {0}};
  PngHandles h;
  std::vector<png_bytep> rows;
  h.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, png_on_error, png_on_warning);
  if (h.png) h.info = png_create_info_struct(h.png);
  if (!h.png || !h.info) {
    *error = "out of memory";
    return DecodeResult::corrupt;
  }
  if (setjmp(png_jmpbuf(h.png))) {
    *error = src.error[0] ? src.error : "corrupt PNG data";
    out->bytes.clear();
    return DecodeResult::corrupt;
  }
  png_set_read_fn(h.png, &src, png_read_bytes);
  png_read_info(h.png, h.info);
  png_uint_32 width = 0, height = 0;
  int depth = 0, color_type = 0, interlace = 0;
  png_get_IHDR(h.png, h.info, &width, &height, &depth, &color_type, &interlace, nullptr, nullptr);
  out->width = int(width);  // libpng refuses more than 2^31 - 1 (and, by default, 10^6) a side
  out->height = int(height);
  out->bits = depth == 16 ? 16 : 8;
  if (exceeds_texel_limit(width, height, options)) return DecodeResult::too_large;
  // Deflate makes at most 1032 bytes of each byte (a 258-byte match in two
  // bits): rows of more bytes than that (filter bytes not counted) cannot be
  // in the file's IDAT data.
  const uint64_t row_bits = uint64_t(width) * uint64_t(depth) * png_get_channels(h.png, h.info);
  const uint64_t packed = (row_bits * height + 7) / 8, compressed = idat_bytes(bytes, size);
  if (packed > deflate_max_ratio * compressed + deflate_max_ratio) {
    *error = "the header declares " + std::to_string(width) + "x" + std::to_string(height) + " texels (" +
             std::to_string(packed) + " bytes of rows), more than its " + std::to_string(compressed) +
             " bytes of compressed data can hold (deflate expands at most " + std::to_string(deflate_max_ratio) +
             " times)";
    return DecodeResult::corrupt;
  }

  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(h.png);
  if (color_type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(h.png);
  if (png_get_valid(h.png, h.info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(h.png);
  if (depth == 16) png_set_swap(h.png);  // big-endian in the file, native (little) here
  png_set_interlace_handling(h.png);
  png_read_update_info(h.png, h.info);
  out->channels = png_get_channels(h.png, h.info);
  const size_t row_bytes = png_get_rowbytes(h.png, h.info);
  if (out->channels < 1 || out->channels > 4 || row_bytes != size_t(width) * out->channels * (out->bits / 8))
    png_error(h.png, "unexpected sample layout");
  if (!charge_decode(uint64_t(row_bytes) * height + uint64_t(height) * sizeof(png_bytep), options, out, error))
    return DecodeResult::over_budget;
  out->bytes.resize(row_bytes * height);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) rows[y] = out->bytes.data() + y * row_bytes;
  png_read_image(h.png, rows.data());
  return DecodeResult::ok;
}

}  // namespace rayform
