#include "rayform/scene/procedural_mesh.h"

#include "rayform/math/hash.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace rayform {

Mesh make_icosphere(int levels) {
  const float t = (1.f + std::sqrt(5.f)) / 2.f;
  Mesh m;
  m.name = "icosphere" + std::to_string(levels);
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (vec3& p : m.positions) p = glm::normalize(p);
  m.indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
               3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto mid = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, uint32_t(m.positions.size()));
      if (inserted) m.positions.push_back(glm::normalize(0.5f * (m.positions[a] + m.positions[b])));
      return it->second;
    };
    std::vector<uint32_t> next;
    next.reserve(m.indices.size() * 4);
    for (size_t i = 0; i < m.indices.size(); i += 3) {
      uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
      uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices = std::move(next);
  }
  m.normals = m.positions;  // unit sphere: the position is the normal
  return m;
}

Mesh make_cube() {
  Mesh m;
  m.name = "cube";
  for (int i = 0; i < 8; ++i) m.positions.push_back(vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
  // Counter-clockwise seen from outside.
  m.indices = {0, 2, 3, 0, 3, 1,   // -z
               4, 5, 7, 4, 7, 6,   // +z
               0, 1, 5, 0, 5, 4,   // -y
               2, 6, 7, 2, 7, 3,   // +y
               0, 4, 6, 0, 6, 2,   // -x
               1, 3, 7, 1, 7, 5};  // +x
  return m;
}

Mesh make_bumpy_torus(size_t target_triangles, uint32_t seed) {
  // rings * segments * 2 ~ target, with segments ~ 3 * rings (the tube is thinner).
  size_t rings = std::max<size_t>(3, size_t(std::sqrt(double(target_triangles) / 6.0)));
  size_t segments = std::max<size_t>(3, (target_triangles + rings) / (2 * rings));
  const float R = 1.f, r = 0.35f;
  // A few random low-frequency bumps.
  float phase[4], freq[4];
  for (int k = 0; k < 4; ++k) {
    phase[k] = (2.f * pi) * hash_to_unit(seed * 4 + k);
    freq[k] = 2.f + std::floor(6.f * hash_to_unit(seed * 4 + k + 100));
  }
  Mesh m;
  m.name = "bumpy_torus";
  m.positions.resize(rings * segments);
  for (size_t i = 0; i < segments; ++i) {  // around the main circle
    float u = (2.f * pi) * float(i) / float(segments);
    for (size_t j = 0; j < rings; ++j) {  // around the tube
      float v = (2.f * pi) * float(j) / float(rings);
      float bump = 0.f;
      for (int k = 0; k < 4; ++k)
        bump += 0.02f * std::sin(freq[k] * (k % 2 ? u : v) + phase[k] + float(k) * u * v * 0.1f);
      float rr = r * (1.f + bump);
      m.positions[i * rings + j] =
          vec3((R + rr * std::cos(v)) * std::cos(u), rr * std::sin(v), (R + rr * std::cos(v)) * std::sin(u));
    }
  }
  m.indices.reserve(rings * segments * 6);
  for (size_t i = 0; i < segments; ++i)
    for (size_t j = 0; j < rings; ++j) {
      uint32_t a = uint32_t(i * rings + j), b = uint32_t(((i + 1) % segments) * rings + j);
      uint32_t c = uint32_t(((i + 1) % segments) * rings + (j + 1) % rings), d = uint32_t(i * rings + (j + 1) % rings);
      m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
    }
  // Smooth normals: area-weighted sum of face normals.
  m.normals.assign(m.positions.size(), vec3(0.f));
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
    vec3 n = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    m.normals[a] += n;
    m.normals[b] += n;
    m.normals[c] += n;
  }
  for (vec3& n : m.normals) n = glm::normalize(n);
  return m;
}

Mesh make_grid(int nx, int ny) {
  Mesh m;
  m.name = "grid";
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      vec2 uv(float(i) / nx, float(j) / ny);
      m.positions.push_back(vec3(uv, 0.f));
      m.normals.push_back(vec3(0.f, 0.f, 1.f));
      m.uvs.push_back(uv);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      uint32_t a = uint32_t(j * (nx + 1) + i), b = a + 1, c = a + uint32_t(nx) + 2, d = a + uint32_t(nx) + 1;
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  return m;
}

}  // namespace rayform
