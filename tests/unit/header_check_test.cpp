// header_check.h: the headers checked before OpenImageIO opens a file (an EXR
// attribute longer than the file, EXR data windows and GIF screens beyond the
// texel limit); ordinary headers pass; and which OpenImageIO reader a file
// gets (oiio_reader_for: from its signature, TGA from its name, else none).
#include "rayform/image/header_check.h"

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

// OpenEXR reads a channel list by its content and a box2i as 16 bytes,
// whatever size they declare, and goes on from there; a fuzzed file used a
// chlist declaring fewer bytes than it holds so that the walk here ended
// early while OpenEXR went on to a string of 1.9 GB.
TEST(HeaderCheck, ExrValueOtherThanItsDeclaredSizeIsRefused) {
  auto with_channels = [](int32_t declared) {
    std::vector<uint8_t> b = {0x76, 0x2f, 0x31, 0x01};
    put32(b, 2);
    put_text(b, "channels");
    put_text(b, "chlist");
    put32(b, declared);
    for (const char* c : {"B", "G", "R"}) {
      put_text(b, c);
      for (int32_t v : {1, 0, 1, 1}) put32(b, v);  // half, pLinear + reserved, sampling 1 1
    }
    b.push_back(0);  // end of the list: 3 x 18 + 1 = 55 bytes
    b.push_back(0);  // end of header
    return b;
  };
  EXPECT_EQ(problem(with_channels(55)), "");
  EXPECT_EQ(problem(with_channels(37)),
            "EXR attribute 'channels' of type chlist declares 37 bytes but its value takes 55");
  std::vector<uint8_t> box = exr(7, 7, 0, 0);
  box[8 + 11 + 6] = 12;  // dataWindow's declared size
  EXPECT_EQ(problem(box), "EXR attribute 'dataWindow' of type box2i declares 12 bytes but its value takes 16");
}

// A preview's size comes from its width and height: 2^32-1 squared times 4
// overflowed the sum (UBSan; found by the fuzzer).
TEST(HeaderCheck, ExrPreviewOfAnySizeIsMeasuredWithoutOverflow) {
  auto with_preview = [](uint32_t w, uint32_t h, int32_t declared) {
    std::vector<uint8_t> b = {0x76, 0x2f, 0x31, 0x01};
    put32(b, 2);
    put_text(b, "preview");
    put_text(b, "preview");
    put32(b, declared);
    put32(b, int32_t(w));
    put32(b, int32_t(h));
    b.insert(b.end(), size_t(declared > 8 ? declared - 8 : 0), 0x7f);
    b.push_back(0);  // end of header
    return b;
  };
  EXPECT_EQ(problem(with_preview(2, 3, 32)), "");  // 8 + 2 x 3 x 4
  EXPECT_EQ(problem(with_preview(2, 3, 20)),
            "EXR attribute 'preview' of type preview declares 20 bytes but its value takes 32");
  EXPECT_EQ(problem(with_preview(0xFFFFFFFFu, 0xFFFFFFFFu, 16)),
            "EXR attribute 'preview' of type preview declares 16 bytes but its value takes more than the 45 bytes of "
            "the file");
}

TEST(HeaderCheck, GifScreenBeyondTheTexelLimit) {
  std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 0x07, 0x38, 0x42, 0x50, 0, 0, 0};
  EXPECT_NE(problem(gif).find("texture is 14343x20546"), std::string::npos) << problem(gif);
  gif[7] = 0x01;  // 263 x 20546: few enough texels, but a side longer than 16384
  EXPECT_NE(problem(gif).find("texture is 263x20546, a side longer than 16384 texels"), std::string::npos)
      << problem(gif);
  gif[8] = 0x00, gif[9] = 0x40;  // 263 x 16384
  EXPECT_EQ(problem(gif), "");
  const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 13, 10, 26, 10};
  EXPECT_EQ(problem(png), "");  // not a format checked here
}

TEST(OiioReaderFor, ChosenFromTheSignatureNotTheName) {
  auto reader = [](const std::string& head, const std::string& name) {
    const char* r = oiio_reader_for(reinterpret_cast<const uint8_t*>(head.data()), head.size(), name);
    return std::string(r ? r : "none");
  };
  EXPECT_EQ(reader(std::string("\x76\x2f\x31\x01\x02\0\0\0", 8), "a.png"), "openexr");
  EXPECT_EQ(reader("#?RADIANCE\n", "a.tif"), "hdr");
  EXPECT_EQ(reader(std::string("II*\0\x08\0\0\0", 8), "a.hdr"), "tiff");
  EXPECT_EQ(reader(std::string("MM\0*\0\0\0\x08", 8), "a"), "tiff");
  EXPECT_EQ(reader("GIF89a", "a.jpg"), "gif");
  EXPECT_EQ(reader("P6\n2 2\n255\n", "a.ppm"), "pnm");
  EXPECT_EQ(reader("8BPS", "a.psd"), "psd");
  // TGA has no signature: its name decides, whatever the bytes.
  EXPECT_EQ(reader(std::string("\0\0\x02\0", 4), "dir.x/A.TGA"), "targa");
  EXPECT_EQ(reader(std::string("\0\0\x02\0", 4), "a.targa"), "targa");
  // The fuzzed ".tif" that OpenImageIO handed to its RLA reader (abort).
  EXPECT_EQ(reader(std::string("\0\0UIDA\0\0", 8), "a.tif"), "none");
  EXPECT_EQ(reader("", "a.exr"), "none");
  EXPECT_EQ(reader("P", "a.ppm"), "none");
  EXPECT_EQ(reader(std::string("P\0", 2), "a.ppm"), "none");
}

}  // namespace
}  // namespace rayform
