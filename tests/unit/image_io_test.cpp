// Image file I/O (src/image/image.h): 8-bit formats quantise by
// floor(clamp(v, 0, 1) * 255) like the course reference; round trips through
// PNG, BMP and EXR; failures throw and leave no file (nor temporary) behind.
#include "rayform/image/image.h"
#include "rayform/math/math.h"
#include "rayform/base/error.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;

TEST(ImageIo, EightBitFormatsQuantiseByFloor) {
  auto dir = test::temp_dir("image_io_floor");
  // value -> expected byte: floor(v * 255) clamped; NaN -> 0.
  const std::vector<std::pair<float, int>> cases = {
      {0.f, 0},
      {1.f, 255},
      {0.5f, 127},  // round-to-nearest would give 128
      {0.999f, 254},
      {0.99999f, 254},
      {1.7f, 255},  // above 1 clamps
      {-0.2f, 0},
      {0.0039f, 0},
      {0.004f, 1},  // 1/255 = 0.0039216
      {100.f / 255.f + 0.002f, 100},
      {std::nanf(""), 0},
      {infinity, 255},
  };
  Image img(int(cases.size()), 1, 1);
  for (size_t i = 0; i < cases.size(); ++i) img.pixels[i] = cases[i].first;
  for (const char* ext : {"png", "bmp", "tga"}) {
    fs::path p = dir / (std::string("q.") + ext);
    Image gray3(img.width, 1, 3);  // BMP wants RGB: same value in all channels
    for (size_t i = 0; i < cases.size(); ++i)
      for (int k = 0; k < 3; ++k) gray3.pixels[3 * i + k] = cases[i].first;
    ASSERT_NO_THROW(write_image(p.string(), gray3)) << ext;
    Image back = read_image(p.string());
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, 1);
    for (size_t i = 0; i < cases.size(); ++i)
      EXPECT_EQ(back.pixels[size_t(back.channels) * i], float(cases[i].second) / 255.f)
          << ext << ": value " << cases[i].first << " should store " << cases[i].second;
  }
  fs::remove_all(dir);
}

// A test picture whose 8-bit values are (7x + 3y + 5c) mod 256, stored as
// (k + 0.5) / 255 so that floor quantisation gives k back.
Image pattern(int w, int h, int c) {
  Image img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) img.at(x, y)[k] = (float((7 * x + 3 * y + 5 * k) % 256) + 0.5f) / 255.f;
  return img;
}

TEST(ImageIo, RoundTripPngAndBmp) {
  auto dir = test::temp_dir("image_io_rt");
  Image img = pattern(37, 5, 3);  // odd width: BMP rows are padded to 4 bytes
  for (const char* ext : {"png", "bmp"}) {
    fs::path p = dir / (std::string("rt.") + ext);
    write_image(p.string(), img);
    Image back = read_image(p.string());
    ASSERT_EQ(back.width, 37) << ext;
    ASSERT_EQ(back.height, 5) << ext;
    ASSERT_EQ(back.channels, 3) << ext;
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 37; ++x)
        for (int k = 0; k < 3; ++k)
          ASSERT_EQ(back.at(x, y)[k], float((7 * x + 3 * y + 5 * k) % 256) / 255.f)
              << ext << " pixel " << x << "," << y << " (row 0 must stay the top row)";
  }
  // A PNG with alpha keeps four channels.
  Image rgba = pattern(4, 3, 4);
  write_image((dir / "a.png").string(), rgba);
  Image back = read_image((dir / "a.png").string());
  ASSERT_EQ(back.channels, 4);
  EXPECT_EQ(back.at(3, 2)[3], float((21 + 6 + 15) % 256) / 255.f);
  fs::remove_all(dir);
}

TEST(ImageIo, RoundTripExrKeepsFloatValues) {
  auto dir = test::temp_dir("image_io_exr");
  Image img(3, 2, 3);
  const float values[] = {-1.5f, 0.f,  1e-3f,   0.123456789f, 1.f,      2.5f,  1000.25f,  1.f / 3.f, 7.f,
                          -0.f,  0.5f, 65504.f, 1e-8f,        3.14159f, 0.75f, 2.f / 7.f, 9.f,       0.1f};
  std::copy(std::begin(values), std::end(values), img.pixels.begin());
  fs::path p = dir / "f.exr";
  write_image(p.string(), img);
  Image back = read_image(p.string());
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  ASSERT_EQ(back.channels, 3);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    EXPECT_EQ(back.pixels[i], img.pixels[i]) << "value " << i << ": EXR must store 32-bit floats, unclamped";
  fs::remove_all(dir);
}

TEST(ImageIo, SuccessfulWriteLeavesOnlyTheTarget) {
  auto dir = test::temp_dir("image_io_ok");
  write_image((dir / "out.png").string(), pattern(4, 4, 3));
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{"out.png"});
  // Overwriting replaces the file and still leaves nothing else.
  write_image((dir / "out.png").string(), pattern(8, 2, 3));
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{"out.png"});
  EXPECT_EQ(read_image((dir / "out.png").string()).width, 8);
  fs::remove_all(dir);
}

void expect_write_fails(const fs::path& target, const Image& img, const fs::path& watched_dir,
                        const std::vector<std::string>& files_before) {
  try {
    write_image(target.string(), img);
    ADD_FAILURE() << "writing " << target << " should fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << "message names the file: " << e.what();
  }
  EXPECT_EQ(test::files_in(watched_dir), files_before) << "a failed write left a file behind in " << watched_dir;
}

TEST(ImageIo, FailedWritesThrowAndLeaveNothing) {
  auto dir = test::temp_dir("image_io_fail");
  Image img = pattern(4, 4, 3);
  // Folder does not exist.
  expect_write_fails(dir / "missing" / "out.png", img, dir, {});
  // Unknown extension.
  expect_write_fails(dir / "out.notanimage", img, dir, {});
  // The target is a folder: the temporary is written, the rename fails.
  fs::create_directory(dir / "taken.png");
  expect_write_fails(dir / "taken.png", img, dir, {"taken.png"});
  EXPECT_TRUE(fs::is_empty(dir / "taken.png"));
  // An empty image cannot be encoded.
  expect_write_fails(dir / "empty.png", Image(), dir, {"taken.png"});
  fs::remove_all(dir);
}

TEST(ImageIo, ReadingAMissingOrBrokenFileThrowsNamingIt) {
  auto dir = test::temp_dir("image_io_read");
  fs::path missing = dir / "nope.png";
  try {
    read_image(missing.string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  fs::path broken = dir / "broken.png";
  { std::ofstream(broken) << "not a png at all"; }
  EXPECT_THROW(read_image(broken.string()), Error);
  fs::remove_all(dir);
}

TEST(ImageIo, WritableExtensions) {
  for (const char* ok : {"a.png", "a.bmp", "a.tga", "a.jpg", "a.exr", "a.hdr", "a.tif", "dir/a.PNG"})
    EXPECT_TRUE(is_writable_image_path(ok)) << ok;
  for (const char* bad : {"a.txt", "a", "a.notanimage"}) EXPECT_FALSE(is_writable_image_path(bad)) << bad;
}

}  // namespace
}  // namespace rayform
