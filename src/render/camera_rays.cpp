#include "rayform/render/camera_rays.h"

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

}  // namespace rayform
