// The in-memory decoders behind image_decode.h, one file each: png_decoder.cpp
// (libpng), jpeg_decoder.cpp (libjpeg-turbo), webp_decoder.cpp (libwebp),
// bmp_reader.cpp (ours: uncompressed 24/32-bit BMP). Each reads the header,
// stops with too_large (dimensions in *out, no pixels) when the image has more
// texels than options.max_texels, and otherwise decodes with the values
// stb_image gave for the same valid file (JPEG: libjpeg's IDCT, see
// jpeg_decoder.cpp).
#pragma once

#include "rayform/image/image_decode.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace rayform {

bool is_png(const uint8_t* bytes, size_t size);
bool is_jpeg(const uint8_t* bytes, size_t size);
bool is_webp(const uint8_t* bytes, size_t size);
// A BMP that bmp_reader.cpp decodes (uncompressed 24/32-bit); other BMPs go to OpenImageIO.
bool is_simple_bmp(const uint8_t* bytes, size_t size);
// Where such a BMP's last pixel row ends (its header's offset + rows x stride); 0 when not one.
uint64_t simple_bmp_bytes(const uint8_t* bytes, size_t size);

// On corrupt, *error says why in a few words.
// PNG: 8-bit (palette, tRNS and 1/2/4-bit grey expanded as stb did) or 16-bit samples.
DecodeResult decode_png(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                        std::string* error);
// JPEG: grey (1 channel) or RGB (CMYK/YCCK converted as stb did).
DecodeResult decode_jpeg(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                         std::string* error);
// WebP: RGBA.
DecodeResult decode_webp(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                         std::string* error);
// BMP: RGB from 24-bit, RGB or RGBA from 32-bit (an all-zero alpha read as opaque, as stb did).
DecodeResult decode_bmp(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                        std::string* error);

}  // namespace rayform
