// Decoding image files that may be hostile (textures of downloaded scenes).
// Every decoder reads the header first and refuses an image whose declared
// size exceeds DecodeOptions::max_texels before a single pixel is decoded or
// allocated, so a few bytes cannot ask for gigabytes (a decompression bomb).
//
// In memory, through libraries that are fuzzed continuously (Debian's
// packages): PNG (libpng), JPEG (libjpeg-turbo), WebP (libwebp), and the
// course's uncompressed 24/32-bit BMP through our own bounds-checked reader
// (bmp_reader.cpp; OpenImageIO would cost every course render ~0.4 s of
// start-up; other BMPs are refused, header_check.h). Everything else (TGA,
// HDR, GIF, PNM, PSD, EXR, TIFF, ...) goes to OpenImageIO's readers
// (oiio_plugin.h), which get the same limit. stb_image, not meant for untrusted files, decodes nothing.
#pragma once

#include "rayform/base/limits.h"
#include "rayform/base/memory_budget.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

struct DecodeOptions {
  // Images of more texels (width * height) are refused before decoding. The
  // default is Limits::texture_texels (base/limits.h: 2^28, 16384 x 16384,
  // the largest texture a GPU accepts; 1 GiB as RGBA8).
  uint64_t max_texels = Limits{}.texture_texels;
  // Charged with the decoded samples (and a decoder's own buffers) after the
  // header is read and before they are allocated; nullptr: job_memory().
  MemoryBudget* memory = nullptr;
  // Bytes a texel the caller makes of the samples while they are held
  // (decode_texture: 4, RGBA8): checked with the samples' charge, so that a
  // texture whose two forms cannot fit is refused before it is decoded.
  uint64_t kept_bytes_per_texel = 0;
};

// Samples as the file stores them: bits 8 (uint8), 16 (uint16, native byte
// order) or 32 (float, linear values as hdr/exr store them). Row 0 = top,
// channels (1-4) interleaved.
struct DecodedImage {
  int width = 0, height = 0, channels = 0, bits = 8;
  std::vector<uint8_t> bytes;  // width * height * channels * bits / 8
  MemoryCharge memory;         // what decoding charged (memory_budget.h): kept while `bytes` are
  std::string note;            // read_image_file: "" or what of the file was ignored (image_extent.h)
};

// over_budget: the samples would pass the memory limit (*error says how much).
enum class DecodeResult { ok, corrupt, too_large, over_budget };

// Charges `bytes` for decoding a width x height texture to options.memory (or
// job_memory()) into out->memory; false with *error set when over the limit.
bool charge_decode(uint64_t bytes, const DecodeOptions& options, DecodedImage* out, std::string* error);

// The longest side a texture may have: the side of a square of max_texels
// (16384 by default). Readers allocate by the width (OpenImageIO's EXR read
// made buffers of 256 rows for a fuzzed 2293761 x 1 file: 7 GB).
uint64_t max_texture_side(const DecodeOptions& options);

// Whether a texture of this size is refused: more than max_texels texels, or
// a side longer than max_texture_side.
inline bool exceeds_texel_limit(uint64_t width, uint64_t height, const DecodeOptions& options) {
  const uint64_t side = max_texture_side(options);
  return width > side || height > side || width * height > options.max_texels;  // (each side < 2^32: no wrap)
}

// Whether decode_image_memory handles these bytes (PNG, JPEG, WebP, or a BMP
// our reader takes); false sends the file to OpenImageIO.
bool decodes_in_memory(const uint8_t* bytes, size_t size);

// Decodes PNG, JPEG, WebP or uncompressed BMP bytes. Throws rayform::Error
// naming `name`: "NAME: texture is WxH (2.1 GB decoded), more than the limit
// of N texels (raise it with --limit texture-texels=N)" when too large, "NAME: cannot decode
// image: REASON" when corrupt, truncated or of another format.
DecodedImage decode_image_memory(const uint8_t* bytes, size_t size, const std::string& name,
                                 const DecodeOptions& options = {});

// The same without throwing: too_large leaves the header's dimensions (and
// no pixels) in *out, corrupt the reason in *error.
DecodeResult decode_image_bytes(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                                std::string* error);

// "texture is WxH (2.1 GB decoded), more than the limit of N texels
// (raise it with --limit texture-texels=N)", or, for a texture within that
// many texels but too long a side, "texture is WxH, a side longer than S
// texels (the side of the limit of N texels; raise it with --limit
// texture-texels=N)"; bytes_per_texel: of the texture it would have made (4
// for RGBA8, 16 for float RGBA).
std::string texture_size_message(uint64_t width, uint64_t height, uint64_t bytes_per_texel,
                                 const DecodeOptions& options);
// Throws rayform::Error "NAME: " + texture_size_message(...) when the size
// exceeds the limit.
void check_texture_size(const std::string& name, uint64_t width, uint64_t height, uint64_t bytes_per_texel,
                        const DecodeOptions& options);

}  // namespace rayform
