#include "rayform/scene/mesh_tangents.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace rayform {
namespace {

// What makes two corners one vertex of the tangent space: position, normal,
// uv (bit-equal, -0 taken as +0) and handedness.
struct CornerKey {
  std::array<uint32_t, 8> bits{};
  bool mirrored = false;
  bool operator==(const CornerKey&) const = default;
};

uint32_t float_bits(float x) { return std::bit_cast<uint32_t>(x + 0.f); }  // x + 0 turns -0 into +0

CornerKey corner_key(vec3 position, vec3 normal, vec2 uv, bool mirrored) {
  CornerKey k;
  const float values[8] = {position.x, position.y, position.z, normal.x, normal.y, normal.z, uv.x, uv.y};
  for (int i = 0; i < 8; ++i) k.bits[size_t(i)] = float_bits(values[i]);
  k.mirrored = mirrored;
  return k;
}

struct CornerKeyHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = k.mirrored ? 0x9e3779b97f4a7c15ull : 0;
    for (uint32_t b : k.bits) h = (h ^ b) * 0x100000001b3ull;  // FNV-1a style mixing
    return size_t(h ^ (h >> 32));
  }
};

// A unit vector perpendicular to the unit vector n (Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited"); (1, 0, 0) when n is zero.
vec3 any_perpendicular(vec3 n) {
  if (n == vec3(0.f)) return vec3(1.f, 0.f, 0.f);
  float sign = std::copysign(1.f, n.z);
  float a = -1.f / (sign + n.z);
  float b = n.x * n.y * a;
  return glm::normalize(vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x));
}

// The angle between the edges from p towards a and towards b; 0 if one has no length.
float corner_angle(vec3 p, vec3 a, vec3 b) {
  vec3 ea = a - p, eb = b - p;
  float la = glm::length(ea), lb = glm::length(eb);
  if (!(la > 0.f) || !(lb > 0.f)) return 0.f;
  return std::acos(std::clamp(glm::dot(ea, eb) / (la * lb), -1.f, 1.f));
}

struct Group {
  vec3 sum{0.f};       // angle-weighted projected tangents
  float weight = 0.f;  // sum of the angles
};

}  // namespace

std::vector<vec4> corner_tangents(const Mesh& mesh, int uv_set) {
  const std::vector<vec2>* uvs = uv_set == 0 ? &mesh.uvs : uv_set == 1 ? &mesh.uvs1 : nullptr;
  if (!uvs || uvs->empty() || uvs->size() != mesh.positions.size()) return {};
  const bool has_normals = mesh.normals.size() == mesh.positions.size();
  const size_t corner_count = mesh.triangle_count() * 3;

  // Per corner: its normal, its triangle's tangent projected and normalised
  // (zero when the triangle is degenerate), the corner's angle, handedness.
  std::vector<vec3> normals(corner_count), directions(corner_count, vec3(0.f));
  std::vector<float> angles(corner_count, 0.f);
  std::vector<bool> mirrored(corner_count, false), degenerate(corner_count, true);
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    uint32_t index[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
    vec3 p[3] = {mesh.positions[index[0]], mesh.positions[index[1]], mesh.positions[index[2]]};
    vec2 uv[3] = {(*uvs)[index[0]], (*uvs)[index[1]], (*uvs)[index[2]]};
    vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    vec3 face = glm::cross(e1, e2);
    float face_length = glm::length(face);
    vec3 face_normal = face_length > 0.f ? face / face_length : vec3(0.f);
    vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
    // e1 = d1.x t + d1.y b, e2 = d2.x t + d2.y b. The determinant's sign is
    // taken as unknown (degenerate uvs) where it is within the rounding
    // bound of its two products.
    float det = d1.x * d2.y - d2.x * d1.y;
    bool uv_degenerate = !(std::abs(det) > gamma_bound(2) * (std::abs(d1.x * d2.y) + std::abs(d2.x * d1.y)));
    vec3 tangent = (e1 * d2.y - e2 * d1.y) / det;
    vec3 bitangent = (e2 * d1.x - e1 * d2.x) / det;
    bool triangle_degenerate = uv_degenerate || !(face_length > 0.f) || !is_finite(tangent) || !is_finite(bitangent);
    for (int k = 0; k < 3; ++k) {
      size_t c = 3 * t + size_t(k);
      vec3 n = face_normal;
      if (has_normals) {
        vec3 vertex_normal = mesh.normals[index[k]];
        float length = glm::length(vertex_normal);
        if (length > 0.f) n = vertex_normal / length;
      }
      normals[c] = n;
      if (triangle_degenerate) continue;
      vec3 projected = tangent - n * glm::dot(n, tangent);
      float length = glm::length(projected);
      if (!(length > 0.f) || !std::isfinite(length)) continue;
      directions[c] = projected / length;
      angles[c] = corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
      mirrored[c] = glm::dot(glm::cross(n, tangent), bitangent) < 0.f;
      degenerate[c] = false;
    }
  }

  // Corners that are one vertex of the tangent space accumulate together.
  std::unordered_map<CornerKey, Group, CornerKeyHash> groups;
  groups.reserve(corner_count);
  std::vector<Group*> corner_group(corner_count);
  for (size_t c = 0; c < corner_count; ++c) {
    uint32_t index = mesh.indices[c];
    Group& g = groups[corner_key(mesh.positions[index], normals[c], (*uvs)[index], mirrored[c])];
    g.sum += directions[c] * angles[c];
    g.weight += angles[c];
    corner_group[c] = &g;  // unordered_map keeps its elements' addresses
  }

  std::vector<vec4> result(corner_count);
  for (size_t c = 0; c < corner_count; ++c) {
    vec3 n = normals[c];
    const Group* g = corner_group[c];
    float w = mirrored[c] ? -1.f : 1.f;
    if (degenerate[c] && !(g->weight > 0.f)) {
      // No tangent of its own: an equal corner's of the other handedness, if any.
      uint32_t index = mesh.indices[c];
      auto other = groups.find(corner_key(mesh.positions[index], n, (*uvs)[index], true));
      if (other != groups.end() && other->second.weight > 0.f) {
        g = &other->second;
        w = -1.f;
      }
    }
    vec3 sum = g->sum - n * glm::dot(n, g->sum);
    float length = glm::length(sum);
    vec3 tangent = sum / length;
    if (!(length > 0.f) || !std::isfinite(length)) {
      tangent = any_perpendicular(n);
      w = 1.f;
    }
    result[c] = vec4(tangent, w);
  }
  return result;
}

}  // namespace rayform
