// The C interface between the core library and librayform_oiio.so.
#pragma once

#include <cstddef>

extern "C" {
// 1 if OpenImageIO can write files named like `path`.
typedef int (*rayform_oiio_can_write_fn)(const char* path);
// Reads as float; *pixels is allocated with malloc (free with rayform_oiio_free). 1 on success.
typedef int (*rayform_oiio_read_fn)(const char* path, int* width, int* height, int* channels, float** pixels,
                                    char* error, size_t error_size);
typedef void (*rayform_oiio_free_fn)(float* pixels);
// Writes `path` in the format named by `format_path`'s extension. 1 on success.
typedef int (*rayform_oiio_write_fn)(const char* format_path, const char* path, int width, int height, int channels,
                                     const float* pixels, char* error, size_t error_size);
}
