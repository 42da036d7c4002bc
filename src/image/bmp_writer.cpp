#include "rayform/image/bmp_writer.h"

#include "rayform/image/checked_write.h"

#include <algorithm>
#include <cstdint>

namespace rayform {
namespace {
constexpr size_t header_bytes = 14 + 40;  // BITMAPFILEHEADER + BITMAPINFOHEADER

void put_u16(unsigned char* at, uint32_t v) {
  at[0] = uint8_t(v);
  at[1] = uint8_t(v >> 8);
}
void put_u32(unsigned char* at, uint32_t v) {
  for (int k = 0; k < 4; ++k) at[k] = uint8_t(v >> (8 * k));
}

// A file row: 3 bytes a pixel, padded with zeros to 4 bytes.
size_t row_bytes(const Image8& img) { return (size_t(img.width) * 3 + 3) & ~size_t(3); }

void encode_header(const Image8& img, unsigned char* head) {
  std::fill(head, head + header_bytes, 0);  // compression, sizes and palette stay 0
  head[0] = 'B';
  head[1] = 'M';
  put_u32(head + 2, uint32_t(header_bytes + row_bytes(img) * size_t(img.height)));
  put_u32(head + 10, uint32_t(header_bytes));  // where the pixels start
  put_u32(head + 14, 40);                      // size of BITMAPINFOHEADER
  put_u32(head + 18, uint32_t(img.width));
  put_u32(head + 22, uint32_t(img.height));  // positive: rows bottom to top
  put_u16(head + 26, 1);                     // planes
  put_u16(head + 28, 24);                    // bits per pixel
}

// File rows [first, first + count) (row 0 is the image's bottom row), BGR and
// padded, to dst.
void encode_rows(const Image8& img, size_t first, size_t count, unsigned char* dst) {
  const size_t w = size_t(img.width), h = size_t(img.height), c = size_t(img.channels), stride = row_bytes(img);
  for (size_t y = first; y < first + count; ++y, dst += stride) {
    const unsigned char* src = img.pixels.data() + (h - 1 - y) * w * c;  // image rows run top to bottom
    unsigned char* out = dst;
    if (c == 3) {
      for (size_t x = 0; x < w; ++x, src += 3, out += 3) {
        out[0] = src[2];
        out[1] = src[1];
        out[2] = src[0];
      }
    } else {
      for (size_t x = 0; x < w; ++x, ++src, out += 3) out[0] = out[1] = out[2] = src[0];
    }
    std::fill(out, dst + stride, 0);
  }
}
}  // namespace

std::vector<unsigned char> encode_bmp24(const Image8& img) {
  std::vector<unsigned char> file(header_bytes + row_bytes(img) * size_t(img.height));
  encode_header(img, file.data());
  encode_rows(img, 0, size_t(img.height), file.data() + header_bytes);
  return file;
}

bool write_bmp24(const std::string& path, const Image8& img, std::string* error) {
  // Row by row through a buffer of about 256 KiB, which stays in the cache
  // and is reused: a whole-file buffer would be as large as the image, and
  // its fresh pages cost more to fault in than the encoding itself.
  const size_t stride = row_bytes(img), h = size_t(img.height);
  const size_t rows_per_block = std::max<size_t>(1, (size_t(256) << 10) / stride);
  std::vector<unsigned char> block(header_bytes + std::min(rows_per_block, h) * stride);
  CheckedFile file;
  if (!file.open(path, error)) return false;
  encode_header(img, block.data());
  size_t head = header_bytes;  // only the first block carries the header
  for (size_t y = 0; y < h || head > 0; y += rows_per_block) {
    const size_t rows = std::min(rows_per_block, h - std::min(y, h));
    encode_rows(img, y, rows, block.data() + head);
    if (!file.write(block.data(), head + rows * stride, error)) return false;
    head = 0;
  }
  return file.finish(error);
}

}  // namespace rayform
