// Decoding untrusted image files (src/image/image_decode.h): every format
// round-trips to known pixel values (files made here with stb_image_write,
// libpng, libjpeg and libwebp), PNG and BMP decode to stb_image's exact bytes,
// truncated files and forged headers give one clean error, and images larger
// than the texel limit are refused before any pixel is allocated, including
// the 23-byte RLE TGA that used to make a 23170x23170 texture and the short
// RLE HDR that used to hang stb_image.
#include "rayform/image/image.h"
#include "rayform/image/image_decode.h"
#include "rayform/base/error.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <jpeglib.h>
#include <png.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <webp/encode.h>
#include <zlib.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

namespace rayform {
namespace {
namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

// 8-bit test pattern: (7x + 3y + 5c + 1) mod 256.
Bytes pattern8(int w, int h, int c) {
  Bytes p(size_t(w) * h * c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) p[(size_t(y) * w + x) * c + k] = uint8_t((7 * x + 3 * y + 5 * k + 1) & 255);
  return p;
}

void append(void* context, void* data, int size) {
  auto* out = static_cast<Bytes*>(context);
  out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
}

Bytes stb_png(int w, int h, int c, const Bytes& px) {
  Bytes out;
  EXPECT_TRUE(stbi_write_png_to_func(append, &out, w, h, c, px.data(), w * c));
  return out;
}
Bytes stb_bmp(int w, int h, int c, const Bytes& px) {
  Bytes out;
  EXPECT_TRUE(stbi_write_bmp_to_func(append, &out, w, h, c, px.data()));
  return out;
}
Bytes stb_tga(int w, int h, int c, const Bytes& px) {
  Bytes out;
  EXPECT_TRUE(stbi_write_tga_to_func(append, &out, w, h, c, px.data()));
  return out;
}
Bytes stb_hdr(int w, int h, int c, const std::vector<float>& px) {
  Bytes out;
  EXPECT_TRUE(stbi_write_hdr_to_func(append, &out, w, h, c, px.data()));
  return out;
}

// libjpeg's encoder at quality 100 (grey or RGB).
Bytes libjpeg_encode(int w, int h, int c, const Bytes& px) {
  jpeg_compress_struct cinfo;
  jpeg_error_mgr jerr;
  cinfo.err = jpeg_std_error(&jerr);
  jpeg_create_compress(&cinfo);
  unsigned char* mem = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&cinfo, &mem, &size);
  cinfo.image_width = JDIMENSION(w);
  cinfo.image_height = JDIMENSION(h);
  cinfo.input_components = c;
  cinfo.in_color_space = c == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, 100, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<uint8_t*>(&px[size_t(cinfo.next_scanline) * w * c]);
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  Bytes out(mem, mem + size);
  jpeg_destroy_compress(&cinfo);
  std::free(mem);
  return out;
}

// 16-bit RGB PNG through libpng's simplified writer (big-endian samples in the file).
Bytes libpng_16bit(int w, int h, const std::vector<uint16_t>& px) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  img.width = png_uint_32(w);
  img.height = png_uint_32(h);
  img.format = PNG_FORMAT_LINEAR_RGB;
  png_alloc_size_t size = 0;
  EXPECT_TRUE(png_image_write_to_memory(&img, nullptr, &size, 0, px.data(), 0, nullptr));
  Bytes out(size);
  EXPECT_TRUE(png_image_write_to_memory(&img, out.data(), &size, 0, px.data(), 0, nullptr));
  out.resize(size);
  return out;
}

Bytes webp_lossless(int w, int h, const Bytes& rgba) {
  uint8_t* mem = nullptr;
  size_t size = WebPEncodeLosslessRGBA(rgba.data(), w, h, w * 4, &mem);
  Bytes out(mem, mem + size);
  WebPFree(mem);
  return out;
}

fs::path write_file(const fs::path& p, const Bytes& bytes) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return p;
}

// The message of the rayform::Error `f` throws ("" when it throws none).
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Runs `f` in a child process; false when it has not finished after `seconds`
// (the child is killed), so that a decoder that hangs fails the test instead
// of stalling the suite.
bool finishes_within(double seconds, const std::function<void()>& f) {
  pid_t pid = fork();
  if (pid == 0) {
    try {
      f();
    } catch (...) {
    }
    _exit(0);
  }
  auto start = std::chrono::steady_clock::now();
  for (;;) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return true;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return false;
    }
    usleep(10000);
  }
}

long max_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

class ImageDecode : public ::testing::Test {
 protected:
  void SetUp() override { dir = test::temp_dir("image_decode"); }
  void TearDown() override { fs::remove_all(dir); }
  fs::path dir;
};

TEST_F(ImageDecode, PngAndBmpDecodeToStbImagesExactBytes) {
  // Odd widths exercise BMP row padding; 1-4 channels PNG, 3 and 4 BMP (stb's
  // 32-bit BMP is a V4 header with BI_BITFIELDS).
  struct Case {
    const char* name;
    Bytes file;
  };
  std::vector<Case> cases;
  for (int c = 1; c <= 4; ++c) cases.push_back({"png", stb_png(13, 7, c, pattern8(13, 7, c))});
  for (int c : {3, 4})
    for (int w : {1, 2, 3, 5, 13}) cases.push_back({"bmp", stb_bmp(w, 6, c, pattern8(w, 6, c))});
  for (const Case& k : cases) {
    SCOPED_TRACE(std::string(k.name) + " of " + std::to_string(k.file.size()) + " bytes");
    ASSERT_TRUE(decodes_in_memory(k.file.data(), k.file.size()));
    DecodedImage ours = decode_image_memory(k.file.data(), k.file.size(), "t");
    int w = 0, h = 0, c = 0;
    stbi_uc* stb = stbi_load_from_memory(k.file.data(), int(k.file.size()), &w, &h, &c, 0);
    ASSERT_NE(stb, nullptr);
    EXPECT_EQ(ours.width, w);
    EXPECT_EQ(ours.height, h);
    EXPECT_EQ(ours.channels, c);
    EXPECT_EQ(ours.bits, 8);
    EXPECT_EQ(ours.bytes, Bytes(stb, stb + size_t(w) * h * c));
    stbi_image_free(stb);
  }
}

TEST_F(ImageDecode, BmpOfTheCourseKindsMatchesStb) {
  // A 24-bit bottom-up BMP as the course writes it, a top-down one (negative
  // height), and a 32-bit BI_RGB one whose alpha bytes are all zero (stb reads
  // such a file as opaque).
  Bytes bottom_up = stb_bmp(5, 3, 3, pattern8(5, 3, 3));
  Bytes top_down = bottom_up;
  int32_t neg = -3;
  std::memcpy(&top_down[22], &neg, 4);
  Bytes bgr0 = {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 1, 0, 32, 0};
  bgr0.resize(54, 0);
  for (uint8_t b : {10, 20, 30, 0, 40, 50, 60, 0}) bgr0.push_back(b);
  for (const Bytes* f : {&bottom_up, &top_down, &bgr0}) {
    DecodedImage ours = decode_image_memory(f->data(), f->size(), "t");
    int w = 0, h = 0, c = 0;
    stbi_uc* stb = stbi_load_from_memory(f->data(), int(f->size()), &w, &h, &c, 0);
    ASSERT_NE(stb, nullptr);
    EXPECT_EQ(ours.channels, c);
    EXPECT_EQ(ours.bytes, Bytes(stb, stb + size_t(w) * h * c));
    stbi_image_free(stb);
  }
  DecodedImage opaque = decode_image_memory(bgr0.data(), bgr0.size(), "t");
  EXPECT_EQ(opaque.bytes, (Bytes{30, 20, 10, 255, 60, 50, 40, 255}));
}

TEST_F(ImageDecode, EveryFormatRoundTripsToKnownValues) {
  const int w = 9, h = 5;
  // PNG, BMP, TGA (stb writes RLE) and WebP (lossless): exact.
  struct Case {
    std::string ext;
    int channels;
    Bytes file;
  };
  std::vector<Case> cases = {{"png", 3, stb_png(w, h, 3, pattern8(w, h, 3))},
                             {"bmp", 3, stb_bmp(w, h, 3, pattern8(w, h, 3))},
                             {"tga", 3, stb_tga(w, h, 3, pattern8(w, h, 3))},
                             {"tga", 4, stb_tga(w, h, 4, pattern8(w, h, 4))},
                             {"webp", 4, webp_lossless(w, h, pattern8(w, h, 4))}};
  int n = 0;
  for (const Case& k : cases) {
    SCOPED_TRACE(k.ext + " with " + std::to_string(k.channels) + " channels");
    fs::path p = write_file(dir / ("a" + std::to_string(n++) + "." + k.ext), k.file);
    DecodedImage d = read_image_file(p.string());
    EXPECT_EQ(d.width, w);
    EXPECT_EQ(d.height, h);
    EXPECT_EQ(d.channels, k.channels);
    EXPECT_EQ(d.bits, 8);
    EXPECT_EQ(d.bytes, pattern8(w, h, k.channels));
  }
  // JPEG at quality 100: a flat grey picture decodes exactly, a smooth RGB
  // gradient within 2 of the original.
  Bytes grey(size_t(16) * 16, 77);
  DecodedImage g = read_image_file(write_file(dir / "g.jpg", libjpeg_encode(16, 16, 1, grey)).string());
  EXPECT_EQ(g.channels, 1);
  EXPECT_EQ(g.bytes, grey);
  Bytes rgb(size_t(16) * 16 * 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int k = 0; k < 3; ++k) rgb[(size_t(y) * 16 + x) * 3 + k] = uint8_t(40 + 4 * x + 3 * y + 20 * k);
  DecodedImage j = read_image_file(write_file(dir / "c.jpeg", libjpeg_encode(16, 16, 3, rgb)).string());
  ASSERT_EQ(j.bytes.size(), rgb.size());
  EXPECT_EQ(j.channels, 3);
  for (size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(int(j.bytes[i]), int(rgb[i]), 2) << "sample " << i;
  // 16-bit PNG: 16-bit samples, and v / 65535 as floats.
  std::vector<uint16_t> px16 = {0, 1, 256, 1000, 32768, 65535};
  DecodedImage p16 = read_image_file(write_file(dir / "d.png", libpng_16bit(2, 1, px16)).string());
  EXPECT_EQ(p16.bits, 16);
  ASSERT_EQ(p16.bytes.size(), 12u);
  std::vector<uint16_t> back(6);
  std::memcpy(back.data(), p16.bytes.data(), 12);
  EXPECT_EQ(back, px16);
  EXPECT_EQ(to_float_image(p16).pixels[4], 32768.f / 65535.f);
  // HDR (OpenImageIO): values RGBE stores exactly.
  std::vector<float> hdr = {0.5f, 1.f, 2.f, 0.25f, 4.f, 8.f, 0.f, 0.f, 0.f, 1.5f, 3.f, 6.f};
  Image hd = read_image(write_file(dir / "e.hdr", stb_hdr(2, 2, 3, hdr)).string());
  EXPECT_EQ(hd.width, 2);
  EXPECT_EQ(hd.channels, 3);
  EXPECT_EQ(hd.pixels, hdr);
}

TEST_F(ImageDecode, TruncatedFilesOfEveryFormatGiveOneCleanError) {
  const int w = 32, h = 32;
  std::vector<std::pair<std::string, Bytes>> files = {
      {"png", stb_png(w, h, 3, pattern8(w, h, 3))},
      {"jpg", libjpeg_encode(w, h, 3, pattern8(w, h, 3))},
      {"webp", webp_lossless(w, h, pattern8(w, h, 4))},
      {"bmp", stb_bmp(w, h, 3, pattern8(w, h, 3))},
      {"tga", stb_tga(w, h, 3, pattern8(w, h, 3))},
      {"hdr", stb_hdr(w, h, 3, std::vector<float>(size_t(w) * h * 3, 0.75f))}};
  for (auto& [ext, bytes] : files) {
    SCOPED_TRACE(ext);
    ASSERT_NO_THROW(read_image_file(write_file(dir / ("whole." + ext), bytes).string()));
    bytes.resize(bytes.size() * 2 / 3);
    fs::path p = write_file(dir / ("cut." + ext), bytes);
    const std::string e = error_of([&] { read_image_file(p.string()); });
    EXPECT_EQ(e.rfind(p.string() + ": cannot decode image", 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

TEST_F(ImageDecode, HugeDimensionsAreRefusedBeforeAnyAllocation) {
  const long rss_before = max_rss_kb();
  // PNG: IHDR rewritten to 100000 x 100000 (40 GB decoded), CRC fixed.
  Bytes png = stb_png(4, 4, 4, pattern8(4, 4, 4));
  const uint8_t side[4] = {0x00, 0x01, 0x86, 0xA0};  // 100000, big-endian
  std::memcpy(&png[16], side, 4);
  std::memcpy(&png[20], side, 4);
  const uLong crc = crc32(0, &png[12], 17);
  for (int i = 0; i < 4; ++i) png[29 + i] = uint8_t(crc >> (24 - 8 * i));
  // JPEG: the SOF0 frame rewritten to 60000 x 60000.
  Bytes jpg = libjpeg_encode(8, 8, 3, pattern8(8, 8, 3));
  size_t sof = 2;
  while (sof + 9 < jpg.size() && !(jpg[sof] == 0xFF && jpg[sof + 1] == 0xC0))
    sof += 2 + (jpg[sof + 2] << 8 | jpg[sof + 3]);
  ASSERT_LT(sof + 9, jpg.size());
  for (size_t at : {sof + 5, sof + 7}) jpg[at] = 0xEA, jpg[at + 1] = 0x60;
  // BMP: a 54-byte header declaring 30000 x 30000 at 24 bits.
  Bytes bmp = stb_bmp(1, 1, 3, pattern8(1, 1, 3));
  int32_t big = 30000;
  std::memcpy(&bmp[18], &big, 4);
  std::memcpy(&bmp[22], &big, 4);
  struct Case {
    std::string ext;
    Bytes file;
    std::string says;
  };
  for (const Case& k : {Case{"png", png, "texture is 100000x100000 (40.0 GB decoded)"},
                        Case{"jpg", jpg, "texture is 60000x60000 (14.4 GB decoded)"},
                        Case{"bmp", bmp, "texture is 30000x30000 (3.6 GB decoded)"}}) {
    fs::path p = write_file(dir / ("big." + k.ext), k.file);
    EXPECT_EQ(error_of([&] { read_image_file(p.string()); }),
              p.string() + ": " + k.says +
                  ", more than the limit of 268435456 texels (raise it with --limit texture-texels=N)");
  }
  EXPECT_LT(max_rss_kb() - rss_before, 100 * 1024) << "kB of peak memory grew while refusing";
}

TEST_F(ImageDecode, TheLimitIsAnOption) {
  fs::path p = write_file(dir / "a.png", stb_png(16, 16, 3, pattern8(16, 16, 3)));
  fs::path q = write_file(dir / "a.webp", webp_lossless(16, 16, pattern8(16, 16, 4)));
  fs::path t = write_file(dir / "a.tga", stb_tga(16, 16, 3, pattern8(16, 16, 3)));
  DecodeOptions exact;
  exact.max_texels = 256;
  DecodeOptions less;
  less.max_texels = 255;
  for (const fs::path& f : {p, q, t}) {
    EXPECT_EQ(read_image_file(f.string(), exact).width, 16);
    EXPECT_EQ(error_of([&] { read_image_file(f.string(), less); }),
              f.string() +
                  ": texture is 16x16 (1.0 kB decoded), more than the limit of 255 texels (raise it with --limit "
                  "texture-texels=N)");
  }
  EXPECT_EQ(DecodeOptions().max_texels, uint64_t(1) << 28);
  EXPECT_EQ(DecodeOptions().max_texels, Limits{}.texture_texels);
}

// Each side is bounded too (the side of the square of the limit): readers
// allocate by the width; OpenImageIO's EXR read asked for 7 GB for a fuzzed
// 2293761 x 1 file within the fuzz entries' 2^22 texels.
TEST_F(ImageDecode, ASideLongerThanTheLimitsSquareIsRefused) {
  EXPECT_EQ(max_texture_side(DecodeOptions{}), 16384u);
  EXPECT_EQ(max_texture_side(DecodeOptions{255}), 15u);
  EXPECT_EQ(max_texture_side(DecodeOptions{256}), 16u);
  EXPECT_EQ(max_texture_side(DecodeOptions{~uint64_t(0)}), 0xFFFFFFFFu);
  DecodeOptions options;
  options.max_texels = 256;
  fs::path p = write_file(dir / "wide.png", stb_png(17, 2, 3, pattern8(17, 2, 3)));
  fs::path q = write_file(dir / "wide.webp", webp_lossless(17, 2, pattern8(17, 2, 4)));
  fs::path t = write_file(dir / "wide.tga", stb_tga(2, 17, 3, pattern8(2, 17, 3)));
  for (const fs::path& f : {p, q, t}) {
    const std::string size = f.extension() == ".tga" ? "2x17" : "17x2";
    EXPECT_EQ(error_of([&] { read_image_file(f.string(), options); }),
              f.string() + ": texture is " + size +
                  ", a side longer than 16 texels (the side of the limit of 256 texels; raise it with --limit "
                  "texture-texels=N)");
  }
  fs::path ok = write_file(dir / "ok.png", stb_png(16, 2, 3, pattern8(16, 2, 3)));
  EXPECT_EQ(read_image_file(ok.string(), options).width, 16);
}

// The 23 bytes that used to render after 39 s at 4.1 GB: an RLE true-colour
// TGA header declaring 23170 x 23170 at 32 bits, then a single RLE packet.
TEST_F(ImageDecode, The23ByteRleTgaBombIsRefusedFromItsHeader) {
  Bytes tga = {0, 0, 10, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x82, 0x5A, 0x82, 0x5A, 32, 8, 0xFF, 1, 2, 3, 4};
  ASSERT_EQ(tga.size(), 23u);
  fs::path p = write_file(dir / "bomb.tga", tga);
  // Refused from the header, before any pixel is decoded: the message is the
  // texel limit's. (No wall-clock bound here: the first read also opens the
  // OpenImageIO plugin, seconds on a loaded machine.)
  EXPECT_EQ(error_of([&] { read_image_file(p.string()); }),
            p.string() +
                ": texture is 23170x23170 (2.1 GB decoded), more than the limit of 268435456 texels "
                "(raise it with --limit texture-texels=N)");
  // Under a limit that lets it through, the 5 bytes of pixel data are not
  // enough for the 1024 x 1024 it declares: an error, not a picture.
  tga[12] = tga[14] = 0x00;
  tga[13] = tga[15] = 0x04;
  fs::path q = write_file(dir / "short.tga", tga);
  EXPECT_TRUE(finishes_within(10, [&] { read_image_file(q.string()); }));
  EXPECT_NE(error_of([&] { read_image_file(q.string()); }).find(": cannot decode image"), std::string::npos);
}

// Radiance RLE scanlines whose run count is 0: stb_image's HDR loader never
// advanced and spun forever on such a file.
TEST_F(ImageDecode, AShortRleHdrThatHungStbGivesACleanError) {
  std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 64\n";
  Bytes hdr(header.begin(), header.end());
  for (uint8_t b : {2, 2, 0, 64, 0, 0, 0, 0}) hdr.push_back(b);  // scanline header, then counts of 0
  fs::path p = write_file(dir / "spin.hdr", hdr);
  EXPECT_TRUE(finishes_within(10, [&] { read_image_file(p.string()); })) << "decoding did not finish";
  const std::string e = error_of([&] { read_image_file(p.string()); });
  EXPECT_EQ(e.rfind(p.string() + ": cannot decode image", 0), 0u) << e;
}

}  // namespace
}  // namespace rayform
