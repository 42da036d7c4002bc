// exr_writer.h: files that OpenImageIO (OpenEXR) reads back to the very float
// bits written (negative, infinite and NaN values too), with the header
// OpenImageIO's own writer gave (capDate aside), for 1x1 to heights not a
// multiple of 16, 1 to 4 channels, compressible and incompressible blocks;
// the same bytes on one thread and on several.
#include "rayform/image/exr_writer.h"

#include "rayform/base/thread_limit.h"
#include "rayform/image/oiio_plugin.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

namespace rayform {
namespace {
namespace fs = std::filesystem;

// Smooth ramps (blocks that deflate), or random bits in the first 16 rows (a
// block stored as it is) and noise in the left half below, and special values.
Image patterned(int w, int h, int channels, bool noisy) {
  Image img(w, h, channels);
  uint32_t state = 777u + uint32_t(w * 13 + h * 5 + channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        state = state * 1664525u + 1013904223u;
        float v = 0.25f * float(x + c) / float(w) + 0.5f * float(y) / float(h) - 0.1f;
        if (noisy && y < 16) v = std::bit_cast<float>(state);  // any bits (NaNs too): the block does not deflate
        if (noisy && y >= 16 && x < (w + 1) / 2) v = std::bit_cast<float>((state & 0x807fffffu) | 0x3f000000u);
        img.at(x, y)[c] = v;
      }
  img.pixels[0] = -2.5f;
  if (img.pixels.size() > 3) {
    img.pixels[1] = std::numeric_limits<float>::infinity();
    img.pixels[2] = -std::numeric_limits<float>::infinity();
    img.pixels[3] = std::numeric_limits<float>::quiet_NaN();
  }
  return img;
}

std::vector<uint8_t> file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// The header's attributes (name, type, value) but capDate, and the header's end.
std::vector<uint8_t> header_without_date(const std::vector<uint8_t>& exr) {
  std::vector<uint8_t> kept(exr.begin(), exr.begin() + 8);
  size_t p = 8;
  while (p < exr.size() && exr[p] != 0) {
    const size_t name_end = std::find(exr.begin() + long(p), exr.end(), 0) - exr.begin();
    const size_t type_end = std::find(exr.begin() + long(name_end) + 1, exr.end(), 0) - exr.begin();
    if (type_end + 4 > exr.size()) break;
    uint32_t size = 0;
    std::memcpy(&size, &exr[type_end + 1], 4);
    const size_t end = type_end + 5 + size;
    if (std::string(exr.begin() + long(p), exr.begin() + long(name_end)) != "capDate")
      kept.insert(kept.end(), exr.begin() + long(p), exr.begin() + long(std::min(end, exr.size())));
    p = end;
  }
  EXPECT_LT(p, exr.size()) << "no end of header";
  return kept;
}

TEST(ExrWriter, ReadsBackAsTheBitsWrittenWithOpenImageIOsHeader) {
  const fs::path dir = test::temp_dir("exr_writer");
  const int sizes[][2] = {{1, 1}, {3, 16}, {7, 17}, {64, 33}, {333, 50}};
  for (const auto& size : sizes)
    for (int channels = 1; channels <= 4; ++channels)
      for (bool noisy : {false, true}) {
        SCOPED_TRACE(std::to_string(size[0]) + "x" + std::to_string(size[1]) + "x" + std::to_string(channels) +
                     (noisy ? " noisy" : ""));
        const Image img = patterned(size[0], size[1], channels, noisy);
        std::string error;
        const fs::path ours = dir / "ours.exr", theirs = dir / "theirs.exr";
        ASSERT_TRUE(write_exr(ours.string(), img, &error)) << error;
        const DecodedImage back = read_image_file(ours.string());
        EXPECT_EQ(back.width, img.width);
        EXPECT_EQ(back.height, img.height);
        ASSERT_EQ(back.channels, img.channels);
        ASSERT_EQ(back.bits, 32);
        ASSERT_EQ(back.bytes.size(), img.pixels.size() * 4);
        EXPECT_EQ(std::memcmp(back.bytes.data(), img.pixels.data(), back.bytes.size()), 0);
        ASSERT_TRUE(oiio_write(theirs.string(), theirs.string(), img, &error)) << error;
        EXPECT_TRUE(header_without_date(file_bytes(ours)) == header_without_date(file_bytes(theirs)));
      }
}

TEST(ExrWriter, TheBytesDoNotDependOnTheThreads) {
  const Image img = patterned(500, 300, 4, true);
  ExrOptions options;
  options.capture_date = "2026:01:02 03:04:05";
  std::vector<uint8_t> one, several;
  {
    auto bound = limit_threads(1);
    one = encode_exr(img, options);
  }
  {
    auto bound = limit_threads(4);
    several = encode_exr(img, options);
  }
  EXPECT_TRUE(one == several);
  const std::string date = "2026:01:02 03:04:05";
  EXPECT_NE(std::search(one.begin(), one.end(), date.begin(), date.end()), one.end());
}

TEST(ExrWriter, RefusesWhatItCannotWrite) {
  const fs::path dir = test::temp_dir("exr_writer_refuses");
  std::string error;
  EXPECT_FALSE(write_exr((dir / "a.exr").string(), Image(0, 2, 3), &error));
  EXPECT_NE(error.find("0x2x3"), std::string::npos) << error;
  EXPECT_FALSE(write_exr((dir / "missing" / "a.exr").string(), Image(2, 2, 3), &error));
  EXPECT_NE(error.find("open"), std::string::npos) << error;
}

}  // namespace
}  // namespace rayform
