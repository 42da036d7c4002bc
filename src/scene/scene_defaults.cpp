#include "scene/scene_defaults.h"

#include "scene/scene_stats.h"

#include <algorithm>
#include <cmath>

namespace rayform {

bool add_default_camera(Scene& scene) {
  if (!scene.cameras.empty()) return false;
  Camera c;
  c.name = "default";
  c.projection = Camera::Projection::perspective;
  c.aspect = Camera::Aspect::fit;
  c.up_vector = Camera::UpVector::orthonormal;
  c.fov_deg = default_camera_fov_deg;
  c.direction = vec3(0.f, 0.f, -1.f);
  c.up = vec3(0.f, 1.f, 0.f);
  const Bounds3 b = scene_stats(scene).bounds;
  if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi)) {
    c.center = vec3(0.f, 0.f, 5.f);
  } else {
    // Camera at (cx, cy, cz + d) looking down -z. A box corner at (x, y, z)
    // relative to the centre lies in view when |x|, |y| <= t (d - z), with
    // t = tan(fov / 2) (vertical; horizontally at least as much for images
    // at least as wide as tall). The worst corner gives
    //   d = h.z + max(h.x, h.y) / t,  h = half extent;
    // the 10% margin widens the framed half size.
    const vec3 h = 0.5f * b.extent();
    const float t = std::tan(radians(c.fov_deg) * 0.5f);
    float half = 1.1f * std::max(h.x, h.y);
    if (!(half > 0.f)) half = std::max(h.z, 1e-3f);  // flat along x and y: a line or a point
    const float d = h.z + half / t;
    c.center = b.center() + vec3(0.f, 0.f, d);
  }
  scene.cameras.push_back(c);
  return true;
}

bool add_headlight(Scene& scene, int camera) {
  if (!scene.lights.empty()) return false;
  Light l;
  l.name = "headlight";
  l.kind = Light::Kind::directional;
  l.color = vec3(1.f);
  if (camera < 0 || camera >= int(scene.cameras.size())) camera = 0;
  l.direction = scene.cameras.empty() ? vec3(0.f, 0.f, -1.f) : glm::normalize(scene.cameras[size_t(camera)].direction);
  if (!is_finite(l.direction)) l.direction = vec3(0.f, 0.f, -1.f);
  scene.lights.push_back(l);
  return true;
}

}  // namespace rayform
