#include "rayform/render/camera_rays.h"

#include "rayform/accel/simd4.h"

#include <algorithm>
#include <cstddef>
#include <cmath>
#include <numbers>

namespace rayform {

CameraFrame make_camera_frame(const Camera& c, int width, int height) {
  CameraFrame f;
  f.origin = c.center;
  f.w = glm::normalize(c.direction);
  f.u = glm::normalize(glm::cross(f.w, c.up));
  f.v = c.up_vector == Camera::UpVector::raw ? c.up : glm::cross(f.u, f.w);
  f.focal = float(1.0 / std::tan(double(c.fov_deg) * std::numbers::pi / 360.0));
  f.width_m1 = float(width - 1);
  f.height_m1 = float(height - 1);
  if (c.aspect == Camera::Aspect::fit) f.sx = float(width) / float(height);
  f.orthographic = c.projection == Camera::Projection::orthographic;
  f.half_height = 0.5f * c.ortho_height;
  return f;
}

PixelCentreRays::PixelCentreRays(const CameraFrame& f, int width, int height) : origin_(f.origin), fw_(f.focal * f.w) {
  for (int i = 0; i < width; ++i) {
    const vec3 xu = image_x(f, float(i)) * f.u;
    for (int a = 0; a < 3; ++a) xu_[a].push_back(xu[a]);
  }
  yv_.reserve(size_t(height));
  for (int j = 0; j < height; ++j) yv_.push_back(image_y(f, float(j)) * f.v);
}

void PixelCentreRays::rays8(int i, int n, int j, Ray* rays) const {
  if (n < 8) {
    for (int l = 0; l < 8; ++l) rays[l] = ray(i + std::min(l, n - 1), j);
    return;
  }
  using namespace simd;
  // glm::normalize(xu + yv + fw): v * (1 / sqrt((v.x v.x + v.y v.y) + v.z v.z)).
  const vec3 yv = yv_[size_t(j)];
  for (int half = 0; half < 8; half += 4) {
    f4 d[3];
    for (int a = 0; a < 3; ++a) d[a] = loadu(&xu_[a][size_t(i + half)]) + splat(yv[a]) + splat(fw_[a]);
    const f4 scale = splat(1.f) / vsqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int a = 0; a < 3; ++a) d[a] = d[a] * scale;
#if RAYFORM_SIMD4_SSE
    // Each ray as two 16-byte halves, (origin, direction.x) and
    // (direction.y, direction.z, tmin = 0, tmax = infinity), by shuffles.
    static_assert(sizeof(Ray) == 32 && offsetof(Ray, direction) == 12 && offsetof(Ray, tmin) == 24 &&
                  offsetof(Ray, tmax) == 28);
    const __m128 o = _mm_setr_ps(origin_.x, origin_.y, origin_.z, 0.f);
    const __m128 limits = _mm_setr_ps(0.f, infinity, 0.f, infinity);
    const __m128 oz = _mm_set1_ps(origin_.z);
    const __m128 ozdx[2] = {_mm_unpacklo_ps(oz, d[0].v), _mm_unpackhi_ps(oz, d[0].v)};         // (oz, dx_l, oz, dx_l+1)
    const __m128 dyz[2] = {_mm_unpacklo_ps(d[1].v, d[2].v), _mm_unpackhi_ps(d[1].v, d[2].v)};  // (dy_l, dz_l, ...)
    for (int pair = 0; pair < 2; ++pair) {
      float* r0 = reinterpret_cast<float*>(rays + half + 2 * pair);
      float* r1 = reinterpret_cast<float*>(rays + half + 2 * pair + 1);
      _mm_storeu_ps(r0, _mm_shuffle_ps(o, ozdx[pair], _MM_SHUFFLE(1, 0, 1, 0)));
      _mm_storeu_ps(r0 + 4, _mm_shuffle_ps(dyz[pair], limits, _MM_SHUFFLE(1, 0, 1, 0)));
      _mm_storeu_ps(r1, _mm_shuffle_ps(o, ozdx[pair], _MM_SHUFFLE(3, 2, 1, 0)));
      _mm_storeu_ps(r1 + 4, _mm_shuffle_ps(dyz[pair], limits, _MM_SHUFFLE(1, 0, 3, 2)));
    }
#else
    alignas(16) float dir[3][4];
    for (int a = 0; a < 3; ++a) store(dir[a], d[a]);
    for (int l = 0; l < 4; ++l) {
      Ray& r = rays[half + l];
      r.origin = origin_;
      r.direction = vec3(dir[0][l], dir[1][l], dir[2][l]);
      r.tmin = 0.f;
      r.tmax = infinity;
    }
#endif
  }
}

}  // namespace rayform
