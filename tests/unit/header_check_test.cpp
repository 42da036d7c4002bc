// header_check.h: the headers checked before OpenImageIO opens a file (an EXR
// attribute longer than the file, EXR data windows and GIF screens beyond the
// texel limit); ordinary headers pass.
#include "image/header_check.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace rayform {
namespace {

void put32(std::vector<uint8_t>& b, int32_t v) {
  for (int k = 0; k < 4; ++k) b.push_back(uint8_t(uint32_t(v) >> (8 * k)));
}
void put_text(std::vector<uint8_t>& b, const std::string& s) {
  b.insert(b.end(), s.begin(), s.end());
  b.push_back(0);
}

// An EXR header: magic, version 2, a dataWindow box, an attribute of
// `extra_size` declared bytes (`extra_have` of them present), the end.
std::vector<uint8_t> exr(int32_t x1, int32_t y1, int32_t extra_size, size_t extra_have) {
  std::vector<uint8_t> b = {0x76, 0x2f, 0x31, 0x01};
  put32(b, 2);
  put_text(b, "dataWindow");
  put_text(b, "box2i");
  put32(b, 16);
  for (int32_t v : {0, 0, x1, y1}) put32(b, v);
  put_text(b, "comments");
  put_text(b, "string");
  put32(b, extra_size);
  b.insert(b.end(), extra_have, 'x');
  b.push_back(0);  // end of header
  return b;
}

std::string problem(const std::vector<uint8_t>& b, uint64_t max_texels = 1u << 28) {
  return header_problem(b.data(), b.size(), b.size(), DecodeOptions{max_texels});
}

TEST(HeaderCheck, OrdinaryExrPasses) { EXPECT_EQ(problem(exr(1023, 511, 5, 5)), ""); }

TEST(HeaderCheck, ExrAttributeLongerThanTheFileIsRefused) {
  EXPECT_EQ(problem(exr(7, 7, 1862270977, 3)),
            "EXR attribute 'comments' declares 1862270977 bytes, more than the 69 "
            "bytes of the file");
  EXPECT_NE(problem(exr(7, 7, -5, 3)).find("declares -5 bytes"), std::string::npos);
}

TEST(HeaderCheck, ExrDataWindowBeyondTheTexelLimit) {
  EXPECT_EQ(problem(exr(99, 99, 0, 0), 10000), "");
  EXPECT_EQ(problem(exr(100, 99, 0, 0), 10000),
            "texture is 101x100 (161.6 kB decoded), more than the limit of 10000 texels (raise it with --limit "
            "texture-texels=N)");
}

TEST(HeaderCheck, GifScreenBeyondTheTexelLimit) {
  std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 0x07, 0x38, 0x42, 0x50, 0, 0, 0};
  EXPECT_NE(problem(gif).find("texture is 14343x20546"), std::string::npos) << problem(gif);
  gif[7] = 0x01;  // 263 x 20546
  EXPECT_EQ(problem(gif), "");
  const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 13, 10, 26, 10};
  EXPECT_EQ(problem(png), "");  // not a format checked here
}

}  // namespace
}  // namespace rayform
