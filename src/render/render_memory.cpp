#include "rayform/render/render_memory.h"

#include "rayform/base/memory_budget.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace rayform {

uint64_t render_memory_bytes(const RenderOptions& o) {
  const bool eight_bit = o.color_format != ColorFormat::linear_float;
  const uint64_t color = eight_bit ? 3 + 3 : 12 + 12;
  uint64_t per_pixel = color;
  if (o.depth) per_pixel += 4 + 12 + 3;
  if (o.normals) per_pixel += 12 + 12 + 3;
  if (o.albedo) per_pixel += color;
  if (o.alpha != AlphaMode::none) per_pixel += 4 + (eight_bit ? 4 : 16);
  // The 3x3-sample grid's sample image (grid_filter.h): colour and hit, and the hit colour with alpha.
  // Adaptive sampling's first-round sums (render.cpp's AdaptiveState).
  if (o.target_error && !o.grid.on()) per_pixel += 56;
  if (o.grid.on()) per_pixel += grid_samples * grid_samples * 4 * (o.alpha != AlphaMode::none ? 7 : 4);
  const uint64_t pixels = uint64_t(std::max(o.width, 0)) * uint64_t(std::max(o.height, 0));
  constexpr uint64_t most = std::numeric_limits<uint64_t>::max();
  return pixels > most / per_pixel ? most : pixels * per_pixel;
}

uint64_t available_memory_bytes() {
  const MemoryBudget& budget = job_memory();
  const uint64_t left = budget.used() < budget.limit() ? budget.limit() - budget.used() : 0;
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return std::max<uint64_t>(std::min(kib * 1024, left), 1);
  return std::max<uint64_t>(left, 1);
}

MemoryCharge charge_mesh_memory(const Scene& scene, const std::vector<uint8_t>& used) {
  uint64_t bytes = 0, meshes = 0, triangles = 0;
  for (size_t i = 0; i < scene.meshes.size() && i < used.size(); ++i) {
    if (!used[i]) continue;
    const uint64_t t = scene.meshes[i].indices.size() / 3;
    bytes += mesh_bytes(scene.meshes[i]) + t * mesh_accel_bytes_per_triangle;
    triangles += t;
    ++meshes;
  }
  return job_memory().charge(bytes, "scene: " + std::to_string(meshes) + (meshes == 1 ? " mesh of " : " meshes of ") +
                                        std::to_string(triangles) + " triangles and their BVHs");
}

uint64_t mesh_bytes(const Mesh& m) {
  return m.positions.size() * sizeof(vec3) + m.normals.size() * sizeof(vec3) + m.uvs.size() * sizeof(vec2) +
         m.uvs1.size() * sizeof(vec2) + m.tangents.size() * sizeof(vec4) + m.colors.size() * sizeof(vec3) +
         m.indices.size() * sizeof(uint32_t) + m.face_materials.size() * sizeof(int);
}

namespace {
std::string gigabytes(uint64_t bytes) {
  char text[32];
  const double gb = double(bytes) / 1e9;
  std::snprintf(text, sizeof text, gb < 10 ? "%.1f GB" : "%.0f GB", gb);
  return text;
}
}  // namespace

std::string render_memory_problem(const RenderOptions& o, uint64_t available) {
  const uint64_t need = render_memory_bytes(o);
  if (available == 0 || need <= available) return "";
  const MemoryBudget& budget = job_memory();
  const uint64_t left = budget.used() < budget.limit() ? budget.limit() - budget.used() : 0;
  return "size: a " + std::to_string(o.width) + "x" + std::to_string(o.height) + " image needs " + gigabytes(need) +
         " for its buffers and files, more than the " + gigabytes(available) + " of memory available" +
         (available == std::max<uint64_t>(left, 1)
              ? " under the memory limit of " + gigabytes(budget.limit()) + " (raise it with --limit memory=N)"
              : "");
}

}  // namespace rayform
