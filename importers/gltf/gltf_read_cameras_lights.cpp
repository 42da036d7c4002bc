// The glTF reader's cameras and KHR_lights_punctual lights (GltfReader,
// gltf_reader_internal.h), placed by the world transform of the node that names
// them.
#include "rayform/importers/gltf/gltf_reader_internal.h"

#include <cmath>
#include <numbers>

namespace rayform::gltf_detail {

void GltfReader::place_camera(int c, const std::string& where, const mat4& world) {
  if (c < 0 || size_t(c) >= model_.cameras.size())
    fail(where + ".camera: camera " + std::to_string(c) + " does not exist (the file has " +
         std::to_string(model_.cameras.size()) + " cameras)");
  const tinygltf::Camera& gc = model_.cameras[size_t(c)];
  const std::string cw = idx("cameras", c);
  Camera cam;
  cam.name = gc.name.empty() ? cw : gc.name;
  cam.aspect = Camera::Aspect::fit;  // the image's shape decides; aspectRatio is not enforced
  cam.up_vector = Camera::UpVector::orthonormal;
  // A glTF camera looks down its local -z with +y up.
  cam.center = transform_point(world, vec3(0.f));
  vec3 dir = transform_vector(world, vec3(0.f, 0.f, -1.f));
  vec3 up = transform_vector(world, vec3(0.f, 1.f, 0.f));
  if (!(glm::length(dir) > 0.f) || !(glm::length(glm::cross(dir, up)) > 0.f) || !is_finite(cam.center)) {
    warn(where + ": the camera's transform is degenerate; camera skipped");
    return;
  }
  cam.direction = glm::normalize(dir);
  cam.up = glm::normalize(up);
  if (gc.type == "perspective") {
    double yfov = gc.perspective.yfov;
    if (!(yfov > 0.0 && yfov < std::numbers::pi))
      fail(cw + ".perspective.yfov: " + std::to_string(yfov) + " is not in (0, pi)");
    cam.projection = Camera::Projection::perspective;
    cam.fov_deg = float(yfov * 180.0 / std::numbers::pi);
  } else if (gc.type == "orthographic") {
    double ymag = gc.orthographic.ymag;
    if (!(std::abs(ymag) > 0.0) || !std::isfinite(ymag)) fail(cw + ".orthographic.ymag: must not be zero");
    cam.projection = Camera::Projection::orthographic;
    cam.ortho_height = float(2.0 * std::abs(ymag));  // ymag is half the view's height
  } else {
    fail(cw + ".type: '" + gc.type + "' is neither perspective nor orthographic");
  }
  scene_.cameras.push_back(cam);
}

// KHR_lights_punctual. Units: point and spot intensity is in candela
// (lm/sr), directional in lux (lm/m^2). The Scene's light colour (scene.h) is
// the radiance a white diffuse surface facing the light gets from it: with
// irradiance E (lux for a directional light; candela / d^2 for point and
// spot lights, whose falloff is inverse square) and Lambert's albedo / pi,
// that is E / pi, so the stored colour is colour x intensity / pi.
void GltfReader::place_light(int li, const std::string& where, const mat4& world) {
  if (li < 0 || size_t(li) >= model_.lights.size())
    fail(where + ".extensions.KHR_lights_punctual.light: light " + std::to_string(li) +
         " does not exist (the file has " + std::to_string(model_.lights.size()) + " lights)");
  const tinygltf::Light& gl = model_.lights[size_t(li)];
  const std::string lw = "extensions.KHR_lights_punctual." + idx("lights", li);
  Light l;
  l.name = gl.name.empty() ? lw : gl.name;
  vec3 color(1.f);
  if (!gl.color.empty()) {
    if (gl.color.size() != 3) fail(lw + ".color: expected 3 numbers, found " + std::to_string(gl.color.size()));
    color = vec3(gl.color[0], gl.color[1], gl.color[2]);
  }
  if (!(gl.intensity >= 0.0) || !std::isfinite(gl.intensity))
    fail(lw + ".intensity: " + std::to_string(gl.intensity) + " is not a finite number >= 0");
  l.color = color * float(gl.intensity / std::numbers::pi);
  l.position = transform_point(world, vec3(0.f));
  vec3 dir = transform_vector(world, vec3(0.f, 0.f, -1.f));  // lights shine down their local -z
  l.direction = glm::length(dir) > 0.f ? glm::normalize(dir) : vec3(0.f, 0.f, -1.f);
  if (gl.type == "directional") {
    l.kind = Light::Kind::directional;
  } else if (gl.type == "point" || gl.type == "spot") {
    l.kind = gl.type == "point" ? Light::Kind::point : Light::Kind::spot;
    l.falloff = 1.f;  // inverse square: candela / d^2 is the irradiance in lux
    if (gl.range < 0.0 || !std::isfinite(gl.range)) fail(lw + ".range: must be a positive number");
    l.range = float(gl.range);
    if (l.kind == Light::Kind::spot) {
      double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle;
      if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2 + 1e-6))
        fail(lw + ".spot: cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2 (found " +
             std::to_string(inner) + ", " + std::to_string(outer) + ")");
      l.spot_inner_deg = float(inner * 180.0 / std::numbers::pi);
      l.spot_outer_deg = float(outer * 180.0 / std::numbers::pi);
    }
  } else {
    fail(lw + ".type: '" + gl.type + "' is not directional, point or spot");
  }
  scene_.lights.push_back(l);
}

}  // namespace rayform::gltf_detail
