// OpenImageIO behind a plugin of ours (librayform_oiio.so), opened with
// dlopen on first use, so that only runs which read a format image_decode.h
// does not decode in memory (tga, hdr, exr, tif, ...) or write one stb does
// not (exr, tif, ...) pay OpenImageIO's start-up cost. The plugin
// is looked up in $RAYFORM_OIIO_PLUGIN, beside the executable, in
// ../lib/rayform relative to it (the installed layout, <prefix>/bin and
// <prefix>/lib/rayform, which the build tree mirrors), then in the install
// folder and the build's <build>/lib/rayform, both compiled in.
#pragma once

#include "rayform/image/image.h"
#include "rayform/image/image_decode.h"

#include <string>

namespace rayform {

// Each throws rayform::Error when the plugin cannot be loaded.
bool oiio_can_write(const std::string& path);
// Reads `path` with OpenImageIO's reader `format` (header_check.h's
// oiio_reader_for), 8-bit files as 8-bit samples, others as float; throws the
// "texture is WxH ..." error of image_decode.h when the header declares more
// than options.max_texels texels (nothing is decoded).
bool oiio_read(const std::string& path, const char* format, const DecodeOptions& options, DecodedImage* image,
               std::string* error);
// 8-bit formats store floor(clamp(v) * 255); float formats the values.
bool oiio_write(const std::string& file_for_format, const std::string& path, const Image& image, std::string* error);

}  // namespace rayform
