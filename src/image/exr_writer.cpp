#include "rayform/image/exr_writer.h"

#include "rayform/base/error.h"
#include "rayform/image/checked_write.h"

#include <libdeflate.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <bit>
#include <cstring>
#include <ctime>
#include <memory>

namespace rayform {
namespace {

constexpr int block_rows = 16;  // rows per chunk of ZIP_COMPRESSION
constexpr uint8_t zip_compression = 3;
constexpr int32_t float_samples = 2;  // the channel list's pixel type FLOAT

struct Bytes {
  std::vector<uint8_t> v;
  void raw(const void* p, size_t n) {
    v.insert(v.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
  }
  void u8(uint8_t x) { v.push_back(x); }
  void i32(int32_t x) {  // little-endian, as every EXR number
    for (int k = 0; k < 4; ++k) v.push_back(uint8_t(uint32_t(x) >> (8 * k)));
  }
  void u64(uint64_t x) {
    for (int k = 0; k < 8; ++k) v.push_back(uint8_t(x >> (8 * k)));
  }
  void f32(float x) { i32(int32_t(std::bit_cast<uint32_t>(x))); }
  void text(const char* s) { raw(s, std::strlen(s) + 1); }  // with its terminating 0
  void attribute(const char* name, const char* type, const Bytes& value) {
    text(name);
    text(type);
    i32(int32_t(value.v.size()));
    raw(value.v.data(), value.v.size());
  }
};

// The channels in the file's order (sorted by name) and the image channel each is.
struct Channel {
  const char* name;
  int source;
};
std::vector<Channel> file_channels(int channels) {
  switch (channels) {
    case 1: return {{"Y", 0}};
    case 2: return {{"G", 1}, {"R", 0}};
    case 3: return {{"B", 2}, {"G", 1}, {"R", 0}};
    default: return {{"A", 3}, {"B", 2}, {"G", 1}, {"R", 0}};
  }
}

std::string now_text() {
  const std::time_t t = std::time(nullptr);
  std::tm local{};
  localtime_r(&t, &local);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y:%m:%d %H:%M:%S", &local);
  return buf;
}

std::vector<uint8_t> header(const Image& image, const std::vector<Channel>& channels, const std::string& date) {
  Bytes h;
  const uint8_t magic_and_version[8] = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};  // version 2, single-part scanlines
  h.raw(magic_and_version, 8);
  Bytes v;
  v.raw(date.c_str(), date.size());  // a string attribute has no terminating 0
  h.attribute("capDate", "string", v);
  v = {};
  for (const Channel& c : channels) {
    v.text(c.name);
    v.i32(float_samples);
    v.i32(0);  // pLinear 0, three reserved bytes
    v.i32(1);  // x sampling
    v.i32(1);  // y sampling
  }
  v.u8(0);
  h.attribute("channels", "chlist", v);
  v = {};
  v.u8(zip_compression);
  h.attribute("compression", "compression", v);
  v = {};
  for (int32_t x : {0, 0, image.width - 1, image.height - 1}) v.i32(x);
  h.attribute("dataWindow", "box2i", v);
  h.attribute("displayWindow", "box2i", v);
  v = {};
  v.u8(0);  // INCREASING_Y
  h.attribute("lineOrder", "lineOrder", v);
  v = {};
  v.f32(1.f);
  h.attribute("pixelAspectRatio", "float", v);
  v = {};
  v.f32(0.f);
  v.f32(0.f);
  h.attribute("screenWindowCenter", "v2f", v);
  v = {};
  v.f32(1.f);
  h.attribute("screenWindowWidth", "float", v);
  h.u8(0);  // end of the header
  return std::move(h.v);
}

uint32_t little_endian_bits(float f) {
  const uint32_t b = std::bit_cast<uint32_t>(f);
  if constexpr (std::endian::native == std::endian::big) return __builtin_bswap32(b);
  return b;
}

// out[i] = in[i] - in[i - 1] + 128 (mod 256), out[0] = in[0]: OpenEXR's ZIP predictor.
void predict(const uint8_t* in, size_t n, uint8_t* out) {
  if (n == 0) return;
  out[0] = in[0];
  size_t i = 1;
#if defined(__SSE2__)
  const __m128i bias = _mm_set1_epi8(char(-128));
  for (; i + 16 <= n; i += 16) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i));
    const __m128i p = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i - 1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm_add_epi8(_mm_sub_epi8(x, p), bias));
  }
#endif
  for (; i < n; ++i) out[i] = uint8_t(in[i] - in[i - 1] + 128);
}

struct Compressor {
  libdeflate_compressor* c;
  std::vector<uint8_t> split, predicted, packed;
  explicit Compressor(int level) : c(libdeflate_alloc_compressor(level)) {
    if (!c) throw Error("EXR: cannot start libdeflate at level " + std::to_string(level));
  }
  Compressor(const Compressor&) = delete;
  ~Compressor() { libdeflate_free_compressor(c); }
};

// One chunk: int32 first row, int32 size, the data (ZIP-compressed rows, or
// the rows as they are where deflate would not make them smaller).
void encode_block(const Image& image, const std::vector<Channel>& channels, int y0, Compressor& z,
                  std::vector<uint8_t>& chunk) {
  const int w = image.width, c = image.channels, y1 = std::min(image.height, y0 + block_rows);
  const size_t samples = size_t(y1 - y0) * size_t(w) * channels.size();
  const size_t raw = samples * 4;
  // The rows as the file lays them out (row by row, in each row channel by
  // channel), split at once into the even and the odd bytes (OpenEXR's
  // reordering): byte 0 and 2 of each sample to the first half, 1 and 3 to the second.
  z.split.resize(raw);  // (per thread: resized once)
  z.predicted.resize(raw);
  z.packed.resize(raw);
  uint8_t* even = z.split.data();
  uint8_t* odd = z.split.data() + raw / 2;
  size_t s = 0;
  for (int y = y0; y < y1; ++y)
    for (const Channel& ch : channels) {
      const float* p = image.pixels.data() + size_t(y) * size_t(w) * size_t(c) + size_t(ch.source);
      for (int x = 0; x < w; ++x, ++s) {
        const uint32_t b = little_endian_bits(p[size_t(x) * size_t(c)]);
        even[2 * s] = uint8_t(b);
        even[2 * s + 1] = uint8_t(b >> 16);
        odd[2 * s] = uint8_t(b >> 8);
        odd[2 * s + 1] = uint8_t(b >> 24);
      }
    }
  predict(z.split.data(), raw, z.predicted.data());
  const size_t packed = libdeflate_zlib_compress(z.c, z.predicted.data(), raw, z.packed.data(), raw - 1);
  const size_t size = packed ? packed : raw;
  chunk.resize(8 + size);
  if (packed) {
    std::memcpy(chunk.data() + 8, z.packed.data(), packed);
  } else {  // no smaller: the rows as they are
    uint8_t* out = chunk.data() + 8;
    for (int y = y0; y < y1; ++y)
      for (const Channel& ch : channels) {
        const float* p = image.pixels.data() + size_t(y) * size_t(w) * size_t(c) + size_t(ch.source);
        for (int x = 0; x < w; ++x, out += 4) {
          const uint32_t b = little_endian_bits(p[size_t(x) * size_t(c)]);
          std::memcpy(out, &b, 4);
        }
      }
  }
  for (int k = 0; k < 4; ++k) {
    chunk[size_t(k)] = uint8_t(uint32_t(y0) >> (8 * k));
    chunk[size_t(4 + k)] = uint8_t(uint32_t(size) >> (8 * k));
  }
}

}  // namespace

std::vector<uint8_t> encode_exr(const Image& image, const ExrOptions& options) {
  const int w = image.width, h = image.height, c = image.channels;
  if (w <= 0 || h <= 0 || c < 1 || c > 4 || image.pixels.size() != size_t(w) * size_t(h) * size_t(c))
    throw Error("EXR: cannot encode a " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c) +
                " image");
  // A chunk's size is an int32: 16 rows of w * c floats must stay below 2^31 bytes.
  if (uint64_t(w) * uint64_t(c) * 4 * block_rows > 0x7fffffffu)
    throw Error("EXR: rows of " + std::to_string(w) + " pixels are too long");
  const std::vector<Channel> channels = file_channels(c);
  std::vector<uint8_t> file = header(image, channels, options.capture_date.empty() ? now_text() : options.capture_date);
  const int blocks = (h + block_rows - 1) / block_rows;
  std::vector<std::vector<uint8_t>> chunks(static_cast<size_t>(blocks));
  tbb::enumerable_thread_specific<std::unique_ptr<Compressor>> compressors;
  tbb::parallel_for(0, blocks, [&](int b) {
    std::unique_ptr<Compressor>& z = compressors.local();
    if (!z) z = std::make_unique<Compressor>(options.level);
    encode_block(image, channels, b * block_rows, *z, chunks[size_t(b)]);
  });
  // The offset table: each chunk's position from the start of the file.
  uint64_t at = file.size() + 8 * uint64_t(blocks);
  Bytes offsets;
  for (const std::vector<uint8_t>& chunk : chunks) {
    offsets.u64(at);
    at += chunk.size();
  }
  file.reserve(at);
  file.insert(file.end(), offsets.v.begin(), offsets.v.end());
  for (std::vector<uint8_t>& chunk : chunks) {
    file.insert(file.end(), chunk.begin(), chunk.end());
    std::vector<uint8_t>().swap(chunk);
  }
  return file;
}

bool write_exr(const std::string& path, const Image& image, std::string* error) {
  std::vector<uint8_t> bytes;
  try {
    bytes = encode_exr(image);
  } catch (const Error& e) {
    *error = e.what();
    return false;
  }
  return write_file_checked(path, bytes.data(), bytes.size(), error);
}

}  // namespace rayform
