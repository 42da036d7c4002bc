// The C interface between the core library and librayform_oiio.so.
#pragma once

#include <cstddef>

extern "C" {
// 1 if OpenImageIO can write files named like `path`.
typedef int (*rayform_oiio_can_write_fn)(const char* path);
// Reads `path` with OpenImageIO's reader named `format` ("openexr", "tiff",
// ...; never a reader OpenImageIO guesses): 1 on success, with *pixels allocated by malloc (free with
// rayform_oiio_free) holding *bits 8 (uint8 samples, when the file's are all
// 8-bit unsigned) or 32 (float) samples; 0 on failure (the reason in `error`);
// 2 when the header declares more than max_texels texels or a side longer
// than max_side, with *width, *height, *channels and *bits set and nothing
// read or allocated; 3, the same, when the samples would take more than
// max_bytes / 2 bytes (the caller copies them). Alpha is returned as stored
// (never premultiplied).
typedef int (*rayform_oiio_read_fn)(const char* path, const char* format, unsigned long long max_texels,
                                    unsigned long long max_side, unsigned long long max_bytes, int* width, int* height,
                                    int* channels, int* bits, void** pixels, char* error, size_t error_size);
typedef void (*rayform_oiio_free_fn)(void* pixels);
// Writes `path` in the format named by `format_path`'s extension. 1 on success.
typedef int (*rayform_oiio_write_fn)(const char* format_path, const char* path, int width, int height, int channels,
                                     const float* pixels, char* error, size_t error_size);
}
