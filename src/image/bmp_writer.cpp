#include "rayform/image/bmp_writer.h"

#include "rayform/image/checked_write.h"

#include <cstdint>

namespace rayform {
namespace {
void put_u16(unsigned char* at, uint32_t v) {
  at[0] = uint8_t(v);
  at[1] = uint8_t(v >> 8);
}
void put_u32(unsigned char* at, uint32_t v) {
  for (int k = 0; k < 4; ++k) at[k] = uint8_t(v >> (8 * k));
}
}  // namespace

std::vector<unsigned char> encode_bmp24(const Image8& img) {
  constexpr size_t header_bytes = 14 + 40;  // BITMAPFILEHEADER + BITMAPINFOHEADER
  const size_t w = size_t(img.width), h = size_t(img.height), c = size_t(img.channels);
  const size_t row_bytes = (w * 3 + 3) & ~size_t(3);
  std::vector<unsigned char> file(header_bytes + row_bytes * h, 0);
  unsigned char* head = file.data();
  head[0] = 'B';
  head[1] = 'M';
  put_u32(head + 2, uint32_t(file.size()));
  put_u32(head + 10, uint32_t(header_bytes));  // where the pixels start
  put_u32(head + 14, 40);                      // size of BITMAPINFOHEADER
  put_u32(head + 18, uint32_t(w));
  put_u32(head + 22, uint32_t(h));  // positive: rows bottom to top
  put_u16(head + 26, 1);            // planes
  put_u16(head + 28, 24);           // bits per pixel; compression, sizes and palette stay 0
  for (size_t y = 0; y < h; ++y) {
    const unsigned char* src = img.pixels.data() + (h - 1 - y) * w * c;  // image rows run top to bottom
    unsigned char* dst = file.data() + header_bytes + y * row_bytes;
    if (c == 3) {
      for (size_t x = 0; x < w; ++x, src += 3, dst += 3) {
        dst[0] = src[2];
        dst[1] = src[1];
        dst[2] = src[0];
      }
    } else {
      for (size_t x = 0; x < w; ++x, ++src, dst += 3) dst[0] = dst[1] = dst[2] = src[0];
    }
  }
  return file;
}

bool write_bmp24(const std::string& path, const Image8& img, std::string* error) {
  const std::vector<unsigned char> file = encode_bmp24(img);
  return write_file_checked(path, file.data(), file.size(), error);
}

}  // namespace rayform
