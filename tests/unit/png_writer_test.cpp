// png_writer.h: files that libpng decodes to the pixels written (the pixels
// stb_image_write's PNG of the same image decodes to), with every chunk's CRC
// right and one zlib stream (zlib's inflate checks its Adler-32), for 1x1,
// odd widths, one row per strip, more rows per strip than the image has, grey
// to RGBA; the same bytes on one thread and on several.
#include "rayform/image/png_writer.h"

#include "rayform/base/thread_limit.h"
#include "rayform/image/image_decode.h"
#include "test_paths.h"

#include <stb_image_write.h>
#include <zlib.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace rayform {
namespace {
namespace fs = std::filesystem;

// Smooth gradients (long runs after filtering) with noise in one corner.
Image8 patterned(int w, int h, int channels) {
  Image8 img{w, h, channels, std::vector<unsigned char>(size_t(w) * size_t(h) * size_t(channels))};
  uint32_t state = 12345u + uint32_t(w * 31 + h * 7 + channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        state = state * 1664525u + 1013904223u;  // LCG: every byte value turns up
        const bool noisy = x < w / 3 && y < h / 2;
        img.pixels[(size_t(y) * w + x) * channels + c] = uint8_t(noisy ? state >> 24 : (x * (c + 1) + y * 3) & 0xff);
      }
  return img;
}

uint32_t get32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// Walks the chunks (checking each CRC), inflates the IDATs' zlib stream and
// returns the filtered bytes; fails the test on any fault.
std::vector<uint8_t> inflated_idat(const std::vector<uint8_t>& png) {
  static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> stream, out;
  EXPECT_TRUE(png.size() >= 8 && std::equal(signature, signature + 8, png.begin()));
  size_t pos = 8;
  std::string last;
  while (pos + 12 <= png.size()) {
    const uint32_t length = get32(&png[pos]);
    EXPECT_LE(pos + 12 + length, png.size());
    if (pos + 12 + length > png.size()) return out;
    const std::string type(png.begin() + long(pos) + 4, png.begin() + long(pos) + 8);
    EXPECT_EQ(get32(&png[pos + 8 + length]), uint32_t(crc32(0, &png[pos + 4], length + 4))) << type;
    if (type == "IDAT") stream.insert(stream.end(), png.begin() + long(pos) + 8, png.begin() + long(pos + 8 + length));
    last = type;
    pos += 12 + length;
  }
  EXPECT_EQ(pos, png.size());
  EXPECT_EQ(last, "IEND");
  z_stream z{};
  EXPECT_EQ(inflateInit(&z), Z_OK);
  out.resize(1 << 16);
  z.next_in = stream.data();
  z.avail_in = uInt(stream.size());
  int status = Z_OK;
  while (status == Z_OK) {
    if (z.total_out == out.size()) out.resize(out.size() * 2);
    z.next_out = out.data() + z.total_out;
    z.avail_out = uInt(out.size() - z.total_out);
    status = inflate(&z, Z_NO_FLUSH);
  }
  EXPECT_EQ(status, Z_STREAM_END) << (z.msg ? z.msg : "");  // a wrong Adler-32 is Z_DATA_ERROR
  EXPECT_EQ(z.avail_in, 0u);                                // nothing after the stream's end
  out.resize(z.total_out);
  inflateEnd(&z);
  return out;
}

std::vector<uint8_t> stb_png(const Image8& img) {
  std::vector<uint8_t> out;
  auto append = [](void* context, void* data, int size) {
    auto* o = static_cast<std::vector<uint8_t>*>(context);
    o->insert(o->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
  };
  EXPECT_TRUE(stbi_write_png_to_func(append, &out, img.width, img.height, img.channels, img.pixels.data(),
                                     img.width * img.channels));
  return out;
}

TEST(PngWriter, DecodesToThePixelsWritten) {
  const int sizes[][2] = {{1, 1}, {1, 9}, {7, 1}, {5, 3}, {17, 33}, {333, 61}, {1001, 130}};
  for (const auto& size : sizes)
    for (int channels = 1; channels <= 4; ++channels)
      for (int strip_rows : {0, 1, 3, 1000}) {
        const Image8 img = patterned(size[0], size[1], channels);
        SCOPED_TRACE(std::to_string(size[0]) + "x" + std::to_string(size[1]) + "x" + std::to_string(channels) +
                     ", strip rows " + std::to_string(strip_rows));
        PngOptions options;
        options.strip_rows = strip_rows;
        const std::vector<uint8_t> png = encode_png(img, options);
        const std::vector<uint8_t> filtered = inflated_idat(png);
        EXPECT_EQ(filtered.size(), size_t(size[1]) * (size_t(size[0]) * channels + 1));
        const DecodedImage ours = decode_image_memory(png.data(), png.size(), "ours.png");
        EXPECT_EQ(ours.width, img.width);
        EXPECT_EQ(ours.height, img.height);
        EXPECT_EQ(ours.channels, img.channels);
        EXPECT_EQ(ours.bits, 8);
        EXPECT_TRUE(ours.bytes == img.pixels);
        if (strip_rows == 0) {  // what the file stb_image_write gave decodes to
          const std::vector<uint8_t> stb = stb_png(img);
          EXPECT_TRUE(decode_image_memory(stb.data(), stb.size(), "stb.png").bytes == ours.bytes);
        }
      }
}

TEST(PngWriter, TheBytesDoNotDependOnTheThreads) {
  const Image8 img = patterned(640, 480, 3);
  std::vector<uint8_t> one, several;
  {
    auto bound = limit_threads(1);
    one = encode_png(img);
  }
  {
    auto bound = limit_threads(4);
    several = encode_png(img);
  }
  EXPECT_TRUE(one == several);
  int idat = 0;
  for (size_t pos = 8; pos + 12 <= one.size(); pos += 12 + get32(&one[pos]))
    idat += std::string(one.begin() + long(pos) + 4, one.begin() + long(pos) + 8) == "IDAT";
  EXPECT_EQ(idat, 4);  // 480 rows of 1921 bytes, 136 rows per 256 KiB strip
}

TEST(PngWriter, WritesTheFile) {
  const fs::path dir = test::temp_dir("png_writer");
  const Image8 img = patterned(64, 48, 4);
  std::string error;
  ASSERT_TRUE(write_png((dir / "a.png").string(), img, &error)) << error;
  std::ifstream in(dir / "a.png", std::ios::binary);
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  EXPECT_TRUE(bytes == encode_png(img));
  EXPECT_FALSE(write_png((dir / "missing" / "a.png").string(), img, &error));
  EXPECT_NE(error.find("open"), std::string::npos) << error;
  EXPECT_FALSE(write_png((dir / "b.png").string(), Image8{0, 3, 3, {}}, &error));
  EXPECT_NE(error.find("0x3x3"), std::string::npos) << error;
}

}  // namespace
}  // namespace rayform
