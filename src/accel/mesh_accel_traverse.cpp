// Traversal of MeshAccel (mesh_accel.h): intersect_mesh (closest hit) and
// occluded_mesh (any hit) run the kernels of mesh_accel_kernel.h, compiled
// twice: with the portable node test (four boxes at a time, simd4.h) and, on
// x86 with GCC or Clang, with the AVX2 one (eight at once), which is used when
// the CPU has AVX2 (RAYFORM_NO_AVX2=1 forces the portable kernels). Both give
// the same results.
#include "rayform/accel/mesh_accel.h"

#include "rayform/accel/mesh_accel_node_test.h"

#include <bit>
#include <cstdlib>

// The kernels with the portable node test: kernel_portable::intersect/occluded.
#define RAYFORM_MESH_KERNEL_FLAVOUR kernel_portable
#include "rayform/accel/mesh_accel_kernel.h"

// The kernels with the AVX2 node test, compiled for AVX2 as a whole:
// kernel_avx2::intersect/occluded.
#if RAYFORM_HAVE_AVX2_KERNEL
#pragma GCC push_options
#pragma GCC target("avx2")
#define RAYFORM_MESH_KERNEL_FLAVOUR kernel_avx2
#include "rayform/accel/mesh_accel_kernel.h"
#include "rayform/accel/mesh_accel_packet8.h"
#pragma GCC pop_options
#endif

namespace rayform {

#if RAYFORM_HAVE_AVX2_KERNEL
namespace {
// AVX2 node tests when the CPU has them (RAYFORM_NO_AVX2=1 forces the portable path).
bool use_avx2() {
  static const bool avx2 = [] {
    const char* off = std::getenv("RAYFORM_NO_AVX2");
    return __builtin_cpu_supports("avx2") && !(off && *off && *off != '0');
  }();
  return avx2;
}
}  // namespace
#endif

bool intersect_mesh(const MeshAccel& m, const Ray& ray, float& tmax, MeshHit* hit) {
#if RAYFORM_HAVE_AVX2_KERNEL
  if (use_avx2()) return kernel_avx2::intersect(m, ray, tmax, hit);
#endif
  return kernel_portable::intersect(m, ray, tmax, hit);
}

int intersect_mesh8(const MeshAccel& m, const Ray* rays, int active, float* tmax, MeshHit* hits) {
#if RAYFORM_HAVE_AVX2_KERNEL
  if (use_avx2() && active) {
    // Rays of one octant go through the packet kernel, the others one by one.
    const int found = kernel_avx2::intersect8(m, rays, active, tmax, hits);
    if (found >= 0) return found;
  }
#endif
  int found = 0;
  for (int i = 0; i < 8; ++i)
    if (((active >> i) & 1) && intersect_mesh(m, rays[i], tmax[i], &hits[i])) found |= 1 << i;
  return found;
}

bool occluded_mesh(const MeshAccel& m, const Ray& ray) {
#if RAYFORM_HAVE_AVX2_KERNEL
  if (use_avx2()) return kernel_avx2::occluded(m, ray);
#endif
  return kernel_portable::occluded(m, ray);
}

}  // namespace rayform
