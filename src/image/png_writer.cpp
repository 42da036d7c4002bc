#include "rayform/image/png_writer.h"

#include "rayform/base/error.h"
#include "rayform/image/checked_write.h"

#include <tbb/parallel_for.h>
#include <zlib.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace rayform {
namespace {

constexpr size_t strip_target_bytes = size_t(256) << 10;  // filtered bytes per strip (PngOptions::strip_rows = 0)
constexpr size_t max_chunk_length = 0x7fffffff;           // PNG chunk lengths are below 2^31

void put32(uint8_t* p, uint32_t v) {
  p[0] = uint8_t(v >> 24);
  p[1] = uint8_t(v >> 16);
  p[2] = uint8_t(v >> 8);
  p[3] = uint8_t(v);
}

// Sets the length and type of an IDAT chunk holding its data after 8 bytes,
// and appends the CRC.
void finish_chunk(std::vector<uint8_t>& chunk) {
  const size_t data = chunk.size() - 8;
  if (data > max_chunk_length) throw Error("PNG: a strip of rows deflates to 2^31 bytes or more");
  put32(chunk.data(), uint32_t(data));
  std::memcpy(chunk.data() + 4, "IDAT", 4);
  chunk.resize(chunk.size() + 4);
  put32(chunk.data() + 8 + data, uint32_t(crc32_z(0, chunk.data() + 4, data + 4)));
}

uint8_t paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// out[i] = row[i] - paeth(left, up, up-left) for one row of `n` bytes with
// `bpp` bytes per pixel; `up` is the previous row (zeros above the first).
void paeth_row(const uint8_t* row, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
  size_t i = 0;
  for (; i < std::min(bpp, n); ++i) out[i] = uint8_t(row[i] - paeth(0, up[i], 0));
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128(), low_bytes = _mm_set1_epi16(0xff);
  auto abs16 = [&](__m128i v) { return _mm_max_epi16(v, _mm_sub_epi16(zero, v)); };
  auto select = [](__m128i mask, __m128i yes, __m128i no) {
    return _mm_or_si128(_mm_and_si128(mask, yes), _mm_andnot_si128(mask, no));
  };
  // Eight bytes at a time in 16-bit lanes (the same arithmetic as paeth()).
  auto half = [&](__m128i x, __m128i a, __m128i b, __m128i c) {
    const __m128i bc = _mm_sub_epi16(b, c), ac = _mm_sub_epi16(a, c);
    const __m128i pa = abs16(bc), pb = abs16(ac), pc = abs16(_mm_add_epi16(bc, ac));
    const __m128i use_a =
        _mm_andnot_si128(_mm_or_si128(_mm_cmpgt_epi16(pa, pb), _mm_cmpgt_epi16(pa, pc)), _mm_set1_epi16(-1));
    const __m128i use_b = _mm_andnot_si128(_mm_cmpgt_epi16(pb, pc), _mm_set1_epi16(-1));
    return _mm_and_si128(_mm_sub_epi16(x, select(use_a, a, select(use_b, b, c))), low_bytes);
  };
  for (; i + 16 <= n; i += 16) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i));
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i - bpp));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(up + i));
    const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(up + i - bpp));
    const __m128i lo = half(_mm_unpacklo_epi8(x, zero), _mm_unpacklo_epi8(a, zero), _mm_unpacklo_epi8(b, zero),
                            _mm_unpacklo_epi8(c, zero));
    const __m128i hi = half(_mm_unpackhi_epi8(x, zero), _mm_unpackhi_epi8(a, zero), _mm_unpackhi_epi8(b, zero),
                            _mm_unpackhi_epi8(c, zero));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm_packus_epi16(lo, hi));
  }
#endif
  for (; i < n; ++i) out[i] = uint8_t(row[i] - paeth(row[i - bpp], up[i], up[i - bpp]));
}

// One strip: its rows filtered and deflated as one IDAT chunk (length, type,
// data, CRC; the last strip's length and CRC are set once the stream's
// Adler-32 follows its data).
struct Strip {
  std::vector<uint8_t> chunk;
  uLong adler = 1;      // Adler-32 of the strip's filtered bytes
  size_t filtered = 0;  // their count
};

void encode_strip(const Image8& image, int y0, int y1, bool first, bool last, Strip& strip) {
  const size_t row_bytes = size_t(image.width) * size_t(image.channels);
  const size_t bpp = size_t(image.channels);
  const uint8_t* pixels = image.pixels.data();
  strip.filtered = size_t(y1 - y0) * (row_bytes + 1);
  if (strip.filtered > 0xffffffffu) throw Error("PNG: a row of " + std::to_string(row_bytes) + " bytes is too long");
  std::vector<uint8_t> filtered(strip.filtered);
  std::vector<uint8_t> zeros(y0 == 0 ? row_bytes : 0);
  for (int y = y0; y < y1; ++y) {
    uint8_t* out = filtered.data() + size_t(y - y0) * (row_bytes + 1);
    out[0] = 4;  // Paeth
    const uint8_t* row = pixels + size_t(y) * row_bytes;
    paeth_row(row, y == 0 ? zeros.data() : row - row_bytes, row_bytes, bpp, out + 1);
  }
  strip.adler = adler32_z(1, filtered.data(), filtered.size());

  z_stream z{};
  // Raw deflate (the zlib header and trailer are ours), run-length matches
  // only: on Paeth residues about as small as zlib's level 1 and faster.
  if (deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_RLE) != Z_OK) throw Error("zlib: cannot start deflate");
  const size_t head = 8 + (first ? 2 : 0);
  strip.chunk.resize(head + deflateBound(&z, uLong(filtered.size())) + 16);
  if (first) {
    strip.chunk[8] = 0x78;  // deflate, 32 KiB window
    strip.chunk[9] = 0x01;  // fastest; (0x78 * 256 + 0x01) % 31 == 0
  }
  z.next_in = filtered.data();
  z.avail_in = uInt(filtered.size());
  size_t used = head;
  int status = Z_OK;
  // The last strip finishes the stream; the others end with a sync flush
  // (an empty stored block, byte-aligned) so that the next strip follows.
  const int flush = last ? Z_FINISH : Z_SYNC_FLUSH;
  do {
    if (used == strip.chunk.size()) strip.chunk.resize(strip.chunk.size() * 2);
    z.next_out = strip.chunk.data() + used;
    z.avail_out = uInt(std::min<size_t>(strip.chunk.size() - used, 1u << 30));
    const uInt before = z.avail_out;
    status = deflate(&z, flush);
    used += before - z.avail_out;
  } while (status == Z_OK && (last || z.avail_out == 0));
  // A flush that had exactly filled the buffer leaves nothing to do: zlib
  // then answers Z_BUF_ERROR to the call that asked for more.
  if (!last && status == Z_BUF_ERROR && z.avail_in == 0 && used > head) status = Z_OK;
  deflateEnd(&z);
  if (status != (last ? Z_STREAM_END : Z_OK)) throw Error("zlib: deflate failed");
  strip.chunk.resize(used);
  if (!last) finish_chunk(strip.chunk);
}

}  // namespace

std::vector<uint8_t> encode_png(const Image8& image, const PngOptions& options) {
  const int w = image.width, h = image.height, c = image.channels;
  if (w <= 0 || h <= 0 || c < 1 || c > 4 || image.pixels.size() != size_t(w) * size_t(h) * size_t(c))
    throw Error("PNG: cannot encode a " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c) +
                " image");
  const size_t row_bytes = size_t(w) * size_t(c) + 1;
  const int strip_rows = options.strip_rows > 0 ? options.strip_rows
                                                : int(std::clamp<size_t>(strip_target_bytes / row_bytes, 1, size_t(h)));
  const int strips = int((int64_t(h) + strip_rows - 1) / strip_rows);
  std::vector<Strip> parts(static_cast<size_t>(strips));
  tbb::parallel_for(0, strips, [&](int i) {
    encode_strip(image, i * strip_rows, std::min(h, (i + 1) * strip_rows), i == 0, i == strips - 1, parts[size_t(i)]);
  });

  uLong adler = 1;
  for (const Strip& s : parts) adler = adler32_combine(adler, s.adler, z_off_t(s.filtered));
  std::vector<uint8_t>& tail = parts.back().chunk;
  tail.resize(tail.size() + 4);
  put32(tail.data() + tail.size() - 4, uint32_t(adler));
  finish_chunk(tail);

  static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const uint8_t iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  size_t total = sizeof signature + 25 + sizeof iend;
  for (const Strip& s : parts) total += s.chunk.size();
  std::vector<uint8_t> png(total);
  uint8_t* p = png.data();
  std::memcpy(p, signature, sizeof signature);
  p += sizeof signature;
  static const uint8_t color_type[5] = {0, 0, 4, 2, 6};  // grey, grey + alpha, RGB, RGBA
  uint8_t* ihdr = p;
  put32(p, 13);
  std::memcpy(p + 4, "IHDR", 4);
  put32(p + 8, uint32_t(w));
  put32(p + 12, uint32_t(h));
  p[16] = 8;  // bits per sample
  p[17] = color_type[c];
  p[18] = p[19] = p[20] = 0;  // deflate, adaptive filtering, no interlace
  put32(p + 21, uint32_t(crc32_z(0, ihdr + 4, 17)));
  p += 25;
  for (Strip& s : parts) {
    std::memcpy(p, s.chunk.data(), s.chunk.size());
    p += s.chunk.size();
    std::vector<uint8_t>().swap(s.chunk);
  }
  std::memcpy(p, iend, sizeof iend);
  return png;
}

bool write_png(const std::string& path, const Image8& image, std::string* error) {
  std::vector<uint8_t> bytes;
  try {
    bytes = encode_png(image);
  } catch (const Error& e) {
    *error = e.what();
    return false;
  }
  return write_file_checked(path, bytes.data(), bytes.size(), error);
}

}  // namespace rayform
