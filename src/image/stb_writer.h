// Writing the everyday formats (bmp, png, tga, jpg; and Radiance hdr) through
// stb_image_write from Debian's libstb-dev (24-bit BMP through our own
// bmp_writer.h, PNG through png_writer.h). Writing is no attack surface: the
// pixels are ours. Reading no longer uses stb_image, which is not meant for
// untrusted files: see image_decode.h. EXR is written by exr_writer.h, other
// formats by OpenImageIO (oiio_plugin.h), loaded on first use.
#pragma once

#include "rayform/image/image.h"

#include <string>

namespace rayform {

// Whether stb writes files with this (lower-case, dotted) extension.
bool stb_writes(const std::string& ext);

// Whether `ext` is one of the 8-bit formats stb writes (bmp, png, tga, jpg).
bool stb_writes_8bit(const std::string& ext);

// `path` is written as is (the caller picks the temporary name); the format
// follows `ext`. 8-bit formats store quantize_unit(v) (image/quantize.h).
bool stb_write(const std::string& path, const std::string& ext, const Image& image, std::string* error);

// An 8-bit image to an 8-bit format (stb_writes_8bit(ext)), values as they are.
bool stb_write8(const std::string& path, const std::string& ext, const Image8& image, std::string* error);

}  // namespace rayform
