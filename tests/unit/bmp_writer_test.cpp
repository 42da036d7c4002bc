// The BMP writer (src/image/bmp_writer.h) gives byte for byte the file that
// stb_image_write's stbi_write_bmp gives, for widths with every row padding
// (0 to 3 bytes), grey and RGB images, and reads back as the same pixels.
#include "rayform/image/bmp_writer.h"
#include "test_paths.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace rayform {
namespace {
namespace fs = std::filesystem;

Image8 patterned(int w, int h, int channels) {
  Image8 img{w, h, channels, std::vector<unsigned char>(size_t(w) * size_t(h) * size_t(channels))};
  uint32_t state = 12345u + uint32_t(w * 31 + h * 7 + channels);
  for (unsigned char& v : img.pixels) {
    state = state * 1664525u + 1013904223u;  // LCG: every byte value turns up
    v = uint8_t(state >> 24);
  }
  return img;
}

std::vector<unsigned char> stb_bytes(const Image8& img) {
  std::vector<unsigned char> out;
  auto append = [](void* context, void* data, int size) {
    auto* o = static_cast<std::vector<unsigned char>*>(context);
    o->insert(o->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  };
  EXPECT_TRUE(stbi_write_bmp_to_func(append, &out, img.width, img.height, img.channels, img.pixels.data()));
  return out;
}

TEST(BmpWriter, SameBytesAsStb) {
  for (int channels : {1, 3})
    for (int w : {1, 2, 3, 4, 5, 17, 64})
      for (int h : {1, 3, 8}) {
        const Image8 img = patterned(w, h, channels);
        const std::vector<unsigned char> ours = encode_bmp24(img), theirs = stb_bytes(img);
        ASSERT_EQ(ours.size(), theirs.size()) << w << "x" << h << "x" << channels;
        EXPECT_EQ(ours, theirs) << w << "x" << h << "x" << channels;
      }
}

TEST(BmpWriter, FileReadsBackAsThePixels) {
  const fs::path dir = test::temp_dir("bmp_writer");
  const Image8 img = patterned(13, 7, 3);
  const std::string path = (dir / "p.bmp").string();
  std::string error;
  ASSERT_TRUE(write_bmp24(path, img, &error)) << error;
  EXPECT_EQ(fs::file_size(path), 54u + 40u * 7u);  // rows of 13 * 3 = 39 bytes padded to 40
  int w = 0, h = 0, c = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &c, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 13);
  EXPECT_EQ(h, 7);
  EXPECT_TRUE(std::equal(img.pixels.begin(), img.pixels.end(), data));
  stbi_image_free(data);
}

// The file is written a block of rows at a time (about 256 KiB): an image of
// several blocks, whose last one is short, gives encode_bmp24's bytes.
TEST(BmpWriter, FileOfManyBlocksIsTheEncodedBytes) {
  const fs::path dir = test::temp_dir("bmp_writer_blocks");
  for (int channels : {1, 3}) {
    const Image8 img = patterned(1001, 419, channels);  // rows of 3004 bytes: 87 a block, 5 blocks
    const std::string path = (dir / ("b" + std::to_string(channels) + ".bmp")).string();
    std::string error;
    ASSERT_TRUE(write_bmp24(path, img, &error)) << error;
    std::ifstream in(path, std::ios::binary);
    const std::vector<unsigned char> written{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::vector<unsigned char> encoded = encode_bmp24(img);
    ASSERT_EQ(written.size(), 54u + 3004u * 419u);
    EXPECT_TRUE(written == encoded) << channels << " channel(s)";
  }
}

TEST(BmpWriter, UnwritablePathFails) {
  const fs::path dir = test::temp_dir("bmp_writer_fail");
  std::string error;
  EXPECT_FALSE(write_bmp24((dir / "no" / "such" / "folder.bmp").string(), patterned(4, 4, 3), &error));
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace rayform
