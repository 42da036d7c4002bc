// Camera ray generation. Pixel (i, j): i = 0..W-1 left to right, j = 0..H-1
// bottom to top; continuous coordinates (i + dx, j + dy) allow sub-pixel
// samples. Image coordinates x = 2i/(W-1) - 1, y = 2j/(H-1) - 1 put the
// outermost pixel centres on +-1 (the course convention).
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/scene/scene.h"

#include <vector>

namespace rayform {

struct CameraFrame {
  vec3 origin;
  vec3 u, v, w;              // right, up (image plane), forward
  float focal = 1.f;         // D = 1 / tan(fov/2), computed in double
  float sx = 1.f, sy = 1.f;  // scale of the image coordinates (aspect)
  float half_height = 1.f;   // orthographic: half the view height
  bool orthographic = false;
  float width_m1 = 1.f, height_m1 = 1.f;  // W - 1, H - 1
};

CameraFrame make_camera_frame(const Camera& camera, int width, int height);

// Image coordinates x, y of continuous pixel coordinates (i, j).
inline float image_x(const CameraFrame& f, float i) {
  return (f.width_m1 > 0.f ? 2.f * i / f.width_m1 - 1.f : 0.f) * f.sx;  // one column: centre
}
inline float image_y(const CameraFrame& f, float j) {
  return (f.height_m1 > 0.f ? 2.f * j / f.height_m1 - 1.f : 0.f) * f.sy;
}

// The ray through continuous pixel coordinates (i, j) (j from the bottom).
inline Ray camera_ray(const CameraFrame& f, float i, float j) {
  const float x = image_x(f, i), y = image_y(f, j);
  Ray r;
  if (f.orthographic) {
    r.origin = f.origin + f.half_height * (x * f.u + y * f.v);
    r.direction = f.w;
  } else {
    r.origin = f.origin;
    r.direction = glm::normalize(x * f.u + y * f.v + f.focal * f.w);
  }
  r.tmin = 0.f;
  return r;
}

// The rays of a perspective camera through pixel centres, camera_ray's float
// operations in camera_ray's order (so bit for bit its rays), with the terms
// that depend on one coordinate computed once per column (x u) and per row
// (y v) instead of once per ray.
class PixelCentreRays {
 public:
  PixelCentreRays(const CameraFrame& f, int width, int height);

  // camera_ray(f, float(i), float(j)) for the perspective frame f.
  [[gnu::always_inline]] Ray ray(int i, int j) const {
    Ray r;
    r.origin = origin_;
    r.direction = glm::normalize(vec3(xu_[0][size_t(i)], xu_[1][size_t(i)], xu_[2][size_t(i)]) + yv_[size_t(j)] + fw_);
    r.tmin = 0.f;
    return r;
  }

  // The rays of the n (1 to 8) pixels (i + l, j), l < n, into rays[l]; lanes
  // n to 7 repeat the last ray. Four lanes at a time (SIMD).
  void rays8(int i, int n, int j, Ray* rays) const;

 private:
  vec3 origin_, fw_;
  std::vector<float> xu_[3];  // x u of every column, by component
  std::vector<vec3> yv_;      // y v of every row
};

}  // namespace rayform
