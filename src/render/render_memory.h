// The memory an image needs, checked before anything is allocated: a render
// whose buffers cannot fit is refused with one line instead of ending in
// std::bad_alloc (or the machine swapping) after the scene was loaded.
#pragma once

#include "rayform/base/memory_budget.h"
#include "rayform/render/render.h"
#include "rayform/scene/scene.h"

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
// /proc/meminfo; 0 when unknown), and no more than what is left of the job's
// memory limit (job_memory(), memory_budget.h).
uint64_t available_memory_bytes();

// The bytes of a mesh's arrays as imported (positions, normals, uvs, ...).
uint64_t mesh_bytes(const Mesh& mesh);
// The bytes prepare's BVH over `triangles` takes while it is built and after
// (mesh_accel.h's nodes, packets and triangle order, and the build's
// per-triangle bounds and references): mesh_accel_bytes_per_triangle each.
inline constexpr uint64_t mesh_accel_bytes_per_triangle = 160;
// Charges job_memory() with the meshes of `scene` whose `used` entry is
// non-zero and their BVHs, or throws rayform::Error "scene: 3 meshes of
// 2000000 triangles and their BVHs need ... (raise it with --limit memory=N)".
MemoryCharge charge_mesh_memory(const Scene& scene, const std::vector<uint8_t>& used);

// "" when render_memory_bytes(options) fits in `available` bytes (or
// `available` is 0: unknown), else e.g. "size: a 100000x100000 image needs
// 560 GB for its buffers and files, more than the 21 GB of memory available"
// (+ " under the memory limit of 1.6 GB (raise it with --limit memory=N)" when
// `available` is what is left of job_memory()'s limit).
std::string render_memory_problem(const RenderOptions& options, uint64_t available);

}  // namespace rayform
