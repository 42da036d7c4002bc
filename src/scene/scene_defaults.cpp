#include "rayform/scene/scene_defaults.h"

#include "rayform/base/error.h"
#include "rayform/scene/scene_stats.h"

#include <algorithm>
#include <cmath>

namespace rayform {
namespace {

bool usable(const Bounds3& b) { return !b.empty() && is_finite(b.lo) && is_finite(b.hi); }

}  // namespace

std::string orbit_problem(const Orbit& orbit) {
  if (!std::isfinite(orbit.azimuth_deg)) return "azimuth AZ must be a finite number of degrees";
  if (!(orbit.elevation_deg > -90.f && orbit.elevation_deg < 90.f))
    return "elevation EL must lie strictly between -90 and 90 degrees";
  if (orbit.distance && !(*orbit.distance > 0.f && std::isfinite(*orbit.distance)))
    return "distance DIST must be a finite number greater than 0";
  return {};
}

vec3 framing_target(const Bounds3& bounds) { return usable(bounds) ? bounds.center() : vec3(0.f); }

Camera orbit_camera(const Bounds3& bounds, const Orbit& orbit, float fov_deg) {
  if (std::string problem = orbit_problem(orbit); !problem.empty()) throw Error("orbit: " + problem);
  if (!(fov_deg > 0.f && fov_deg < 180.f)) throw Error("orbit: the field of view must lie strictly between 0 and 180");
  Camera c;
  c.projection = Camera::Projection::perspective;
  c.aspect = Camera::Aspect::fit;
  c.up_vector = Camera::UpVector::orthonormal;
  c.fov_deg = fov_deg;
  c.up = vec3(0.f, 1.f, 0.f);
  // The camera's frame: `back` from the centre to the camera, `right` and
  // `top` across the image. At (0, 0) they are exactly +z, +x and +y.
  const float az = radians(orbit.azimuth_deg), el = radians(orbit.elevation_deg);
  const float sa = std::sin(az), ca = std::cos(az), se = std::sin(el), ce = std::cos(el);
  const vec3 back(sa * ce, se, ca * ce), right(ca, 0.f, -sa), top(-sa * se, ce, -ca * se);
  c.direction = vec3(0.f) - back;  // 0 - 0 is +0: the default camera's direction bit for bit
  float d = 5.f;
  if (orbit.distance) {
    d = *orbit.distance;
  } else if (usable(bounds)) {
    // A box corner at (x, y, z) in the camera's frame, relative to the
    // centre, lies in view when |x|, |y| <= t (d - z), with t = tan(fov / 2)
    // (vertical; horizontally at least as much for images at least as wide
    // as tall). The box's half extents in that frame (h projected on each
    // axis) bound every corner, so
    //   d = h_back + max(h_right, h_top) / t
    // suffices; the 10% margin widens the framed half size.
    const vec3 h = 0.5f * bounds.extent();
    const float hr = glm::dot(glm::abs(right), h), ht = glm::dot(glm::abs(top), h), hb = glm::dot(glm::abs(back), h);
    const float t = std::tan(radians(fov_deg) * 0.5f);
    float half = 1.1f * std::max(hr, ht);
    if (!(half > 0.f)) half = std::max(hb, 1e-3f);  // flat across the view: a line or a point
    d = hb + half / t;
  }
  c.center = framing_target(bounds) + d * back;
  if (!is_finite(c.center)) throw Error("orbit: the camera's position is out of range");
  return c;
}

Orbit default_orbit(const Bounds3& bounds) {
  if (!usable(bounds)) return Orbit{};
  const vec3 e = bounds.extent();
  auto thin = [&](int axis) { return e[axis] < flat_bounds_fraction * std::min(e[(axis + 1) % 3], e[(axis + 2) % 3]); };
  if (thin(2)) return Orbit{};  // facing the default camera already
  if (thin(1)) return Orbit{0.f, flat_view_elevation_deg, std::nullopt};
  if (thin(0)) return Orbit{90.f, 0.f, std::nullopt};
  return Orbit{};
}

vec3 up_not_parallel(vec3 up, vec3 direction) {
  auto parallel = [&](vec3 u) {
    const float ld = glm::length(direction), lu = glm::length(u);
    return !(glm::length(glm::cross(direction, u)) > 1e-6f * ld * lu);
  };
  if (!parallel(up)) return up;
  if (!parallel(vec3(0.f, 1.f, 0.f))) return vec3(0.f, 1.f, 0.f);
  return vec3(0.f, 0.f, direction.y < 0.f ? -1.f : 1.f);
}

bool add_default_camera(Scene& scene) {
  if (!scene.cameras.empty()) return false;
  const Bounds3 bounds = scene_stats(scene).bounds;
  Camera c = orbit_camera(bounds, default_orbit(bounds));
  c.name = "default";
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

bool add_light_rig(Scene& scene, int camera) {
  if (!scene.lights.empty()) return false;
  if (camera < 0 || camera >= int(scene.cameras.size())) camera = 0;
  // The camera's frame: `back` towards the viewer, `right` and `top` across the image.
  vec3 back(0.f, 0.f, 1.f), right(1.f, 0.f, 0.f), top(0.f, 1.f, 0.f);
  if (!scene.cameras.empty()) {
    const Camera& c = scene.cameras[size_t(camera)];
    const vec3 forward = glm::normalize(c.direction);
    if (is_finite(forward)) {
      const vec3 side = glm::normalize(glm::cross(forward, up_not_parallel(c.up, forward)));
      if (is_finite(side)) {
        back = -forward;
        right = side;
        top = glm::cross(right, forward);
      }
    }
  }
  for (const RigLight& r : light_rig) {
    Light l;
    l.name = r.name;
    l.kind = Light::Kind::directional;
    l.color = vec3(r.intensity);
    l.direction = -glm::normalize(r.to_light.x * right + r.to_light.y * top + r.to_light.z * back);
    scene.lights.push_back(l);
  }
  return true;
}

}  // namespace rayform
