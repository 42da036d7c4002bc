// Cube-map background lookup with the course's face conventions. The face is
// chosen by the direction's major axis (ties go to x, then y, then z); with
// a = the major component, the face coordinates are
//   +x right: ((z/a + 1)/2,     (y/a + 1)/2)     -x left:  ((z/a + 1)/2, 1 - (y/a + 1)/2)
//   +y up:    ((x/a + 1)/2,     (z/a + 1)/2)     -y down:  (1 - (x/a + 1)/2, 1 - (z/a + 1)/2)
//   +z front: (1 - (x/a + 1)/2, (y/a + 1)/2)     -z back:  ((x/a + 1)/2, 1 - (y/a + 1)/2)
// and each face is sampled like a course texture (texel centres on whole numbers).
#pragma once

#include "rayform/render/texture_sampler.h"

#include <cmath>
#include <vector>

namespace rayform {

// Faces in the order of Background::cube_map: face = 2 * major axis + (1 if
// the major component is negative).
enum CubeFace { cube_right = 0, cube_left, cube_up, cube_down, cube_front, cube_back };

// Per face: the axes giving s and t, and whether each is flipped (1 - x).
struct CubeFaceLayout {
  int s_axis, t_axis;
  bool flip_s, flip_t;
};
inline constexpr CubeFaceLayout cube_face_layouts[6] = {
    {2, 1, false, false},  // right
    {2, 1, false, true},   // left
    {0, 2, false, false},  // up
    {0, 2, true, true},    // down
    {0, 1, true, false},   // front
    {0, 1, false, true},   // back
};

inline vec3 sample_cube_map(const std::vector<TextureImage>& faces, vec3 direction) {
  vec3 d = glm::normalize(direction);
  vec3 a = glm::abs(d);
  const int major = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
  const int face = 2 * major + (d[major] > 0.f ? 0 : 1);
  const CubeFaceLayout& layout = cube_face_layouts[face];
  const float s = (d[layout.s_axis] / d[major] + 1.f) * 0.5f, t = (d[layout.t_axis] / d[major] + 1.f) * 0.5f;
  const vec2 uv(layout.flip_s ? 1.f - s : s, layout.flip_t ? 1.f - t : t);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return vec3(0.f);  // zero or NaN direction
  return vec3(sample_texture(faces[face], uv));
}

}  // namespace rayform
