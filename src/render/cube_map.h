// Cube-map background lookup with the course's face conventions. The face is
// chosen by the direction's major axis (ties go to x, then y, then z); with
// a = the major component, the face coordinates are
//   +x right: ((z/a + 1)/2,     (y/a + 1)/2)     -x left:  ((z/a + 1)/2, 1 - (y/a + 1)/2)
//   +y up:    ((x/a + 1)/2,     (z/a + 1)/2)     -y down:  (1 - (x/a + 1)/2, 1 - (z/a + 1)/2)
//   +z front: (1 - (x/a + 1)/2, (y/a + 1)/2)     -z back:  ((x/a + 1)/2, 1 - (y/a + 1)/2)
// and each face is sampled like a course texture (texel centres on whole numbers).
#pragma once

#include "render/texture_sampler.h"

#include <cmath>
#include <vector>

namespace rayform {

// Faces in the order of Background::cube_map.
enum CubeFace { cube_right = 0, cube_left, cube_up, cube_down, cube_front, cube_back };

inline vec3 sample_cube_map(const std::vector<TextureImage>& faces, vec3 direction) {
  vec3 d = glm::normalize(direction);
  vec3 a = glm::abs(d);
  int face;
  vec2 uv;
  if (a.x >= a.y && a.x >= a.z) {
    float s = (d.z / d.x + 1.f) * 0.5f, t = (d.y / d.x + 1.f) * 0.5f;
    if (d.x > 0.f) {
      face = cube_right;
      uv = vec2(s, t);
    } else {
      face = cube_left;
      uv = vec2(s, 1.f - t);
    }
  } else if (a.y >= a.z) {
    float s = (d.x / d.y + 1.f) * 0.5f, t = (d.z / d.y + 1.f) * 0.5f;
    if (d.y > 0.f) {
      face = cube_up;
      uv = vec2(s, t);
    } else {
      face = cube_down;
      uv = vec2(1.f - s, 1.f - t);
    }
  } else {
    float s = (d.x / d.z + 1.f) * 0.5f, t = (d.y / d.z + 1.f) * 0.5f;
    if (d.z > 0.f) {
      face = cube_front;
      uv = vec2(1.f - s, t);
    } else {
      face = cube_back;
      uv = vec2(s, 1.f - t);
    }
  }
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return vec3(0.f);  // zero or NaN direction
  return vec3(sample_texture(faces[face], uv));
}

}  // namespace rayform
