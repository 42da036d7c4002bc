#include "rayform/image/image_decode.h"

#include "rayform/image/image_decoders.h"
#include "rayform/base/error.h"
#include "rayform/base/memory_budget.h"

#include <algorithm>
#include <cmath>

namespace rayform {

uint64_t max_texture_side(const DecodeOptions& options) {
  // floor(sqrt(max_texels)), exact; sides are below 2^32 (squares do not wrap).
  constexpr uint64_t most = 0xFFFFFFFFu;
  uint64_t side = std::min<uint64_t>(uint64_t(std::sqrt(double(options.max_texels))), most);
  while (side * side > options.max_texels) --side;
  while (side < most && (side + 1) * (side + 1) <= options.max_texels) ++side;
  return side;
}

std::string texture_size_message(uint64_t width, uint64_t height, uint64_t bytes_per_texel,
                                 const DecodeOptions& options) {
  const uint64_t texels = width * height;
  if (texels <= options.max_texels)
    return "texture is " + std::to_string(width) + "x" + std::to_string(height) + ", a side longer than " +
           std::to_string(max_texture_side(options)) + " texels (the side of the limit of " +
           std::to_string(options.max_texels) + " texels; raise it with --limit texture-texels=N)";
  const uint64_t bytes = texels > UINT64_MAX / bytes_per_texel ? UINT64_MAX : texels * bytes_per_texel;
  return "texture is " + std::to_string(width) + "x" + std::to_string(height) + " (" +
         memory_size_text(bytes, SizeDigits::one_decimal) + " decoded), more than the limit of " +
         std::to_string(options.max_texels) + " texels (raise it with --limit texture-texels=N)";
}

void check_texture_size(const std::string& name, uint64_t width, uint64_t height, uint64_t bytes_per_texel,
                        const DecodeOptions& options) {
  if (exceeds_texel_limit(width, height, options))
    throw Error(name + ": " + texture_size_message(width, height, bytes_per_texel, options));
}

bool charge_decode(uint64_t bytes, const DecodeOptions& options, DecodedImage* out, std::string* error) {
  MemoryBudget& budget = options.memory ? *options.memory : job_memory();
  const uint64_t texels = uint64_t(out->width) * uint64_t(out->height), kept = texels * options.kept_bytes_per_texel;
  const std::string what = "decoding the " + std::to_string(out->width) + "x" + std::to_string(out->height) +
                           " texture" + (kept ? " (and keeping it as " + memory_size_text(kept) + ")" : "");
  // The form kept must fit beside the samples: checked now, charged when made.
  if (std::string problem = budget.problem(bytes + kept, what); !problem.empty()) {
    *error = problem;
    return false;
  }
  try {
    out->memory = budget.charge(bytes, what);
  } catch (const Error& e) {  // (another thread took what was left)
    *error = e.what();
    return false;
  }
  return true;
}

bool decodes_in_memory(const uint8_t* bytes, size_t size) {
  return is_png(bytes, size) || is_jpeg(bytes, size) || is_webp(bytes, size) || is_simple_bmp(bytes, size);
}

DecodeResult decode_image_bytes(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                                std::string* error) {
  if (is_png(bytes, size)) return decode_png(bytes, size, options, out, error);
  if (is_jpeg(bytes, size)) return decode_jpeg(bytes, size, options, out, error);
  if (is_webp(bytes, size)) return decode_webp(bytes, size, options, out, error);
  if (is_simple_bmp(bytes, size)) return decode_bmp(bytes, size, options, out, error);
  *error = "not a PNG, JPEG, WebP or uncompressed BMP file";
  return DecodeResult::corrupt;
}

DecodedImage decode_image_memory(const uint8_t* bytes, size_t size, const std::string& name,
                                 const DecodeOptions& options) {
  DecodedImage out;
  std::string error;
  const DecodeResult r = decode_image_bytes(bytes, size, options, &out, &error);
  if (r == DecodeResult::too_large)
    throw Error(name + ": " +
                texture_size_message(uint64_t(out.width), uint64_t(out.height), out.bits == 8 ? 4 : 16, options));
  if (r == DecodeResult::over_budget) throw Error(name + ": " + error);
  if (r != DecodeResult::ok) throw Error(name + ": cannot decode image: " + error);
  return out;
}

}  // namespace rayform
