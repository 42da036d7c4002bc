#include "rayform/importers/shape_tessellation.h"

#include "rayform/scene/scene_stats.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rayform {

Mesh tessellate_sphere(const Sphere& sphere, int segments) {
  segments = std::max(segments, 3);
  const int bands = std::max(2, segments / 2);
  Mesh m;
  m.name = "sphere";
  auto add = [&](vec3 dir) {
    m.positions.push_back(sphere.center + sphere.radius * dir);
    m.normals.push_back(dir);
  };
  // Angles in double so that the rings are symmetric to the last bit.
  add(vec3(0.f, 1.f, 0.f));  // north pole: vertex 0
  for (int i = 1; i < bands; ++i) {
    const double theta = std::numbers::pi * double(i) / double(bands);
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * double(j) / double(segments);
      dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      add(vec3(glm::normalize(d)));
    }
  }
  add(vec3(0.f, -1.f, 0.f));  // south pole: last vertex
  const uint32_t south = uint32_t(m.positions.size() - 1);
  auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * segments + (j % segments)); };
  // Seen from outside, with phi growing counter-clockwise about +y seen from
  // above (x -> -z), triangles (pole, ring j, ring j+1) face outwards.
  for (int j = 0; j < segments; ++j) m.indices.insert(m.indices.end(), {0u, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < bands; ++i)
    for (int j = 0; j < segments; ++j) {
      uint32_t a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  for (int j = 0; j < segments; ++j)
    m.indices.insert(m.indices.end(), {south, ring(bands - 1, j + 1), ring(bands - 1, j)});
  return m;
}

Mesh plane_quad(const Plane& plane, vec3 around, float half_size) {
  vec3 n = glm::normalize(plane.normal);
  const float d = plane.offset / glm::length(plane.normal);
  // Tangents from the axis least aligned with n.
  vec3 a = std::abs(n.x) < 0.9f ? vec3(1.f, 0.f, 0.f) : vec3(0.f, 1.f, 0.f);
  vec3 t = glm::normalize(glm::cross(a, n));
  vec3 b = glm::cross(n, t);
  vec3 c = around - (glm::dot(n, around) - d) * n;
  // Snap the centre onto the plane along the dominant normal axis, so that an
  // axis-aligned plane's vertices satisfy n . p = d exactly.
  int k = max_dimension(glm::abs(n));
  if (std::abs(n[k]) == 1.f) c[k] = d * n[k];
  Mesh m;
  m.name = "plane";
  vec3 corners[4] = {c - half_size * t - half_size * b, c + half_size * t - half_size * b,
                     c + half_size * t + half_size * b, c - half_size * t + half_size * b};
  for (vec3 p : corners) {
    if (std::abs(n[k]) == 1.f) p[k] = c[k];
    m.positions.push_back(p);
    m.normals.push_back(n);
  }
  // (t, b, n) is right-handed: 0,1,2 is counter-clockwise seen from +n.
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Bounds3 scene_extent(const Scene& scene) {
  Bounds3 b;
  if (scene.root != invalid) b = scene_stats(scene).bounds;
  for (const Camera& c : scene.cameras) b.expand(c.center);
  for (const Light& l : scene.lights)
    if (l.kind != Light::Kind::directional) b.expand(l.position);
  return b;
}

}  // namespace rayform
