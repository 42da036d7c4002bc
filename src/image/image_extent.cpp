#include "rayform/image/image_extent.h"

#include "rayform/image/image_decoders.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace rayform {
namespace {

uint32_t be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }
uint32_t le32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// Ancillary data (text, ICC profiles, EXIF, thumbnails) a file may carry
// besides what its pixels need: more is refused.
constexpr uint64_t metadata_bytes = uint64_t(64) << 20;

// Reads of a few bytes at increasing offsets, served from a block of the
// file (a seek for each would make a walk over millions of empty chunks slow).
class BlockReader {
 public:
  explicit BlockReader(std::istream& in) : in_(in), block_(64 * 1024) {}
  bool read_at(uint64_t at, uint8_t* to, size_t n) {
    if (at < start_ || at + n > start_ + size_) {
      in_.clear();
      in_.seekg(std::streamoff(at));
      in_.read(reinterpret_cast<char*>(block_.data()), std::streamsize(block_.size()));
      start_ = at;
      size_ = size_t(in_.gcount());
      if (n > size_) return false;
    }
    std::memcpy(to, block_.data() + (at - start_), n);
    return true;
  }

 private:
  std::istream& in_;
  std::vector<uint8_t> block_;
  uint64_t start_ = 0;
  size_t size_ = 0;
};

std::string past_need(const char* format, uint64_t need, const char* end) {
  return std::string("no ") + end + " within the " + std::to_string(need) + " bytes a " + format +
         " of the size its header declares can need";
}

// PNG: signature, then chunks (length, type, data, CRC) up to IEND. The
// chunks before IEND may take at most twice the image's filtered rows (their
// size as deflate's stored blocks, with room to spare) plus metadata_bytes.
void png_extent(BlockReader& in, ImageExtent* e) {
  uint64_t at = 8, need = metadata_bytes;
  uint8_t h[8 + 13];
  while (true) {
    if (at + 12 > e->file_bytes || !in.read_at(at, h, 8)) {
      return;  // no IEND: the whole file, for the decoder to judge
    }
    const uint64_t length = be32(h);
    if (std::memcmp(h + 4, "IHDR", 4) == 0 && at == 8 && length == 13 && in.read_at(at + 8, h + 8, 13)) {
      const uint64_t w = be32(h + 8), height = be32(h + 12), depth = h[16], type = h[17];
      const uint64_t samples = type == 2 ? 3 : type == 4 ? 2 : type == 6 ? 4 : 1;
      need += 2 * height * (1 + (w * samples * depth + 7) / 8) + 2 * 7 * height;  // (interlaced: 7 passes)
    }
    at += 12 + length;
    if (std::memcmp(h + 4, "IEND", 4) == 0) {
      e->bytes = std::min(at, e->file_bytes);
      return;
    }
    if (at > need + 8) {
      e->problem = past_need("PNG", need, "IEND chunk");
      return;
    }
  }
}

// JPEG: segments (FF marker, length) up to each SOS, whose entropy-coded data
// is scanned for the next marker (FF then neither 00 nor a restart marker),
// until EOI. At most 16 bytes a sample (a baseline block takes at most ~3.3
// bytes a sample, doubled by byte stuffing; progressive refinement scans add
// less again) plus metadata_bytes.
void jpeg_extent(BlockReader& in, std::istream& stream, ImageExtent* e) {
  uint64_t at = 2, need = metadata_bytes;
  std::vector<uint8_t> block(64 * 1024);
  uint8_t h[10];
  while (true) {
    if (at > need) {
      e->problem = past_need("JPEG", need, "EOI marker");
      return;
    }
    if (!in.read_at(at, h, 2) || h[0] != 0xFF) {
      return;  // no EOI: the whole file, for the decoder to judge
    }
    const uint8_t marker = h[1];
    if (marker == 0xFF) {  // fill byte
      at += 1;
      continue;
    }
    if (marker == 0xD9) {  // EOI
      e->bytes = at + 2;
      return;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // TEM, RSTn: no length
      at += 2;
      continue;
    }
    if (!in.read_at(at + 2, h + 2, 2)) {
      return;  // no EOI: the whole file, for the decoder to judge
    }
    const uint64_t length = uint64_t(h[2]) << 8 | h[3];
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof && in.read_at(at + 4, h + 4, 6))
      need += 16 * (uint64_t(h[5]) << 8 | h[6]) * (uint64_t(h[7]) << 8 | h[8]) * h[9];
    at += 2 + length;
    if (marker != 0xDA) continue;
    // Entropy-coded data: up to the next marker.
    bool found = false;
    while (!found) {
      if (at > need) break;
      stream.clear();
      stream.seekg(std::streamoff(at));
      stream.read(reinterpret_cast<char*>(block.data()), std::streamsize(block.size()));
      const size_t n = size_t(stream.gcount());
      if (n < 2) {
        return;
      }
      size_t i = 0;
      for (; i + 1 < n; ++i)
        if (block[i] == 0xFF && block[i + 1] != 0 && !(block[i + 1] >= 0xD0 && block[i + 1] <= 0xD7) &&
            block[i + 1] != 0xFF) {
          found = true;
          break;
        }
      at += i;
    }
  }
}

// WebP: "RIFF", the size of what follows, "WEBP"; the RIFF chunk is the file.
void webp_extent(BlockReader& in, ImageExtent* e) {
  uint8_t h[8];
  if (!in.read_at(0, h, 8)) return;
  const uint64_t size = 8 + uint64_t(le32(h + 4)) + (le32(h + 4) & 1);
  if (size > e->file_bytes)
    e->problem = "the file is truncated (its RIFF header declares " + std::to_string(size) + " bytes, the file has " +
                 std::to_string(e->file_bytes) + ")";
  else e->bytes = size;
}

}  // namespace

ImageExtent image_extent(std::istream& in, uint64_t file_bytes) {
  ImageExtent e;
  e.file_bytes = e.bytes = file_bytes;
  BlockReader blocks(in);
  uint8_t head[256];
  in.clear();
  in.seekg(0);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const size_t n = size_t(in.gcount());
  if (is_png(head, n)) {
    e.format = "PNG";
    png_extent(blocks, &e);
  } else if (is_jpeg(head, n)) {
    e.format = "JPEG";
    jpeg_extent(blocks, in, &e);
  } else if (is_webp(head, n)) {
    e.format = "WebP";
    webp_extent(blocks, &e);
  } else if (is_simple_bmp(head, n)) {
    e.format = "BMP";
    if (const uint64_t end = simple_bmp_bytes(head, n); end != 0 && end < file_bytes) e.bytes = end;
  }
  in.clear();
  return e;
}

std::string trailing_bytes_note(const ImageExtent& e) {
  if (e.bytes >= e.file_bytes || !e.problem.empty()) return "";
  const char* end = e.format == "PNG" ? " (IEND)" : e.format == "JPEG" ? " (EOI)" : e.format == "WebP" ? " (RIFF)" : "";
  return std::to_string(e.file_bytes - e.bytes) + " bytes after the " + e.format + " image's end" + end +
         " are ignored";
}

}  // namespace rayform
