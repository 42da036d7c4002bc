// OpenImageIO behind a plugin of ours (librayform_oiio.so), opened with
// dlopen on first use, so that only runs which read or write a format stb
// does not handle (exr, tif, ...) pay OpenImageIO's start-up cost. The plugin
// is looked up in $RAYFORM_OIIO_PLUGIN, beside the executable, in
// ../lib/rayform relative to it, and in the build's library folder.
#pragma once

#include "image/image.h"

#include <string>

namespace rayform {

// Each throws rayform::Error when the plugin cannot be loaded.
bool oiio_can_write(const std::string& path);
bool oiio_read(const std::string& path, Image* image, std::string* error);
// 8-bit formats store floor(clamp(v) * 255); float formats the values.
bool oiio_write(const std::string& file_for_format, const std::string& path, const Image& image, std::string* error);

}  // namespace rayform
