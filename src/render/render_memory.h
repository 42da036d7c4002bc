// The memory an image needs, checked before anything is allocated: a render
// whose buffers cannot fit is refused with one line instead of ending in
// std::bad_alloc (or the machine swapping) after the scene was loaded.
#pragma once

#include "rayform/render/render.h"

#include <cstdint>
#include <string>

namespace rayform {

// Bytes of the per-pixel buffers render() allocates for `options` plus what
// writing them as files needs (each output converted once and encoded once:
// 8-bit colour 3 + 3 bytes a pixel, float colour 12 + 12, depth 4 + 12 + 3,
// normals 12 + 12 + 3, albedo as colour, coverage 4 and the colour with an
// alpha channel 4 (8-bit) or 16). Saturates instead of overflowing.
uint64_t render_memory_bytes(const RenderOptions& options);

// The memory the system can give this process now (Linux: MemAvailable of
// /proc/meminfo; 0 when unknown).
uint64_t available_memory_bytes();

// "" when render_memory_bytes(options) fits in `available` bytes (or
// `available` is 0: unknown), else e.g. "size: a 100000x100000 image needs
// 560 GB for its buffers and files, more than the 21 GB of memory available".
std::string render_memory_problem(const RenderOptions& options, uint64_t available);

}  // namespace rayform
