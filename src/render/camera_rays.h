// Camera ray generation. Pixel (i, j): i = 0..W-1 left to right, j = 0..H-1
// bottom to top; continuous coordinates (i + dx, j + dy) allow sub-pixel
// samples. Image coordinates x = 2i/(W-1) - 1, y = 2j/(H-1) - 1 put the
// outermost pixel centres on +-1 (the course convention).
#pragma once

#include "rayform/geometry/ray.h"
#include "rayform/scene/scene.h"

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

// The ray through continuous pixel coordinates (i, j) (j from the bottom).
inline Ray camera_ray(const CameraFrame& f, float i, float j) {
  float x = (f.width_m1 > 0.f ? 2.f * i / f.width_m1 - 1.f : 0.f) * f.sx;  // one column: centre
  float y = (f.height_m1 > 0.f ? 2.f * j / f.height_m1 - 1.f : 0.f) * f.sy;
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

}  // namespace rayform
