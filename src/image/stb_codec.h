// The everyday 8-bit formats (bmp, png, tga, jpg; and Radiance hdr) through
// stb_image / stb_image_write from Debian's libstb-dev. They start in no time
// and touch little memory, unlike Debian's OpenImageIO, whose 241 shared
// libraries cost ~134 MB and ~0.4 s at every process start (docs/performance.md);
// every other format goes to OpenImageIO (oiio_plugin.h), loaded on first use.
#pragma once

#include "image/image.h"

#include <string>

namespace rayform {

// Whether stb handles files with this (lower-case, dotted) extension.
bool stb_reads(const std::string& ext);
bool stb_writes(const std::string& ext);

// Decodes to float: 8-bit as v / 255, 16-bit as v / 65535, hdr as stored.
// Returns false and sets *error on failure.
bool stb_read(const std::string& path, Image* image, std::string* error);

// 8-bit decode; false (with *error empty) when the file is hdr or 16-bit.
bool stb_read8(const std::string& path, Image8* image, std::string* error);

// Whether `ext` is one of the 8-bit formats stb writes (bmp, png, tga, jpg).
bool stb_writes_8bit(const std::string& ext);

// `path` is written as is (the caller picks the temporary name); the format
// follows `ext`. 8-bit formats store quantize_unit(v) (image/quantize.h).
bool stb_write(const std::string& path, const std::string& ext, const Image& image, std::string* error);

// An 8-bit image to an 8-bit format (stb_writes_8bit(ext)), values as they are.
bool stb_write8(const std::string& path, const std::string& ext, const Image8& image, std::string* error);

}  // namespace rayform
