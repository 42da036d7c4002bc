// image_extent.h: where a PNG, JPEG, WebP or BMP file's image ends, so that
// what follows (a hostile file: a valid image, then gigabytes of zeros) is
// neither read nor copied; and a walk that passes what the header's size can
// need is refused.
#include "rayform/image/image_extent.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <webp/encode.h>

#include <sstream>
#include <string>
#include <vector>

namespace rayform {
namespace {

void append(void* context, void* data, int size) {
  auto* out = static_cast<std::string*>(context);
  out->append(static_cast<const char*>(data), size_t(size));
}

std::string pixels(int w, int h, int c) {
  std::string p(size_t(w * h * c), '\0');
  for (size_t i = 0; i < p.size(); ++i) p[i] = char(i * 7);
  return p;
}

ImageExtent extent_of(const std::string& bytes) {
  std::istringstream in(bytes);
  return image_extent(in, bytes.size());
}

TEST(ImageExtent, TrailingBytesAfterEachFormatsEndAreLeftOut) {
  const std::string rgb = pixels(8, 8, 3);
  std::string png, jpg, bmp;
  ASSERT_TRUE(stbi_write_png_to_func(append, &png, 8, 8, 3, rgb.data(), 24));
  ASSERT_TRUE(stbi_write_jpg_to_func(append, &jpg, 8, 8, 3, rgb.data(), 90));
  ASSERT_TRUE(stbi_write_bmp_to_func(append, &bmp, 8, 8, 3, rgb.data()));
  uint8_t* webp_out = nullptr;
  const size_t webp_size = WebPEncodeRGB(reinterpret_cast<const uint8_t*>(rgb.data()), 8, 8, 24, 90.f, &webp_out);
  ASSERT_GT(webp_size, 0u);
  const std::string webp(reinterpret_cast<char*>(webp_out), webp_size);
  WebPFree(webp_out);
  const std::string zeros(100000, '\0');
  for (const auto& [format, file] :
       std::vector<std::pair<std::string, std::string>>{{"PNG", png}, {"JPEG", jpg}, {"BMP", bmp}, {"WebP", webp}}) {
    SCOPED_TRACE(format);
    const ImageExtent alone = extent_of(file);
    EXPECT_EQ(alone.format, format);
    EXPECT_EQ(alone.bytes, file.size());
    EXPECT_EQ(trailing_bytes_note(alone), "");
    const ImageExtent padded = extent_of(file + zeros);
    EXPECT_EQ(padded.problem, "");
    EXPECT_EQ(padded.bytes, file.size());
    EXPECT_EQ(padded.file_bytes, file.size() + zeros.size());
  }
  EXPECT_EQ(trailing_bytes_note(extent_of(png + zeros)), "100000 bytes after the PNG image's end (IEND) are ignored");
  EXPECT_EQ(trailing_bytes_note(extent_of(jpg + zeros)), "100000 bytes after the JPEG image's end (EOI) are ignored");
}

TEST(ImageExtent, NoEndWithinWhatTheHeaderCanNeedIsRefused) {
  // An 8x8 PNG cut before IEND, then 70 MB of zeros: empty chunks of no
  // type, past the 64 MB of metadata any PNG may carry.
  const std::string rgb = pixels(8, 8, 3);
  std::string png;
  ASSERT_TRUE(stbi_write_png_to_func(append, &png, 8, 8, 3, rgb.data(), 24));
  png.resize(png.size() - 12);
  const ImageExtent e = extent_of(png + std::string(70u << 20, '\0'));
  EXPECT_EQ(e.problem.rfind("no IEND chunk within the ", 0), 0u) << e.problem;
  // A file that simply ends before IEND is left to the decoder.
  EXPECT_EQ(extent_of(png).problem, "");
  EXPECT_EQ(extent_of(png).bytes, png.size());
  // A WebP whose RIFF header claims more than the file.
  std::string webp = "RIFF";
  webp += std::string("\x40\x00\x00\x00", 4) + "WEBPVP8L" + std::string(20, '\0');
  EXPECT_EQ(extent_of(webp).problem, "the file is truncated (its RIFF header declares 72 bytes, the file has 36)");
}

}  // namespace
}  // namespace rayform
