#include "rayform/importers/obj/obj_smooth_normals.h"

#include "rayform/base/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>

namespace rayform::obj {
namespace {

// A triangle's unit normal weighted by its angle at each corner (where the
// triangle and the corner's edges have a length): what each corner adds to
// its position's sum.
void angle_weighted_normals(const std::vector<tinyobj::index_t>& idx, size_t start, const std::vector<float>& vertices,
                            vec3* weighted, uint8_t* contributes) {
  contributes[0] = contributes[1] = contributes[2] = 0;
  vec3 p[3];
  for (int k = 0; k < 3; ++k) {
    const size_t v = size_t(idx[start + k].vertex_index);
    p[k] = vec3(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
  }
  vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  float len = glm::length(n);
  if (!(len > 0.f) || !std::isfinite(len)) return;
  n /= len;
  for (int k = 0; k < 3; ++k) {
    vec3 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
    float l1 = glm::length(e1), l2 = glm::length(e2);
    if (!(l1 > 0.f && l2 > 0.f)) continue;
    float c = std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.f, 1.f);
    weighted[k] = std::acos(c) * n;
    contributes[k] = 1;
  }
}

// The sums of the positions [lo, hi) into sums[lo, hi): the weighted normals
// of a block of faces at once (only of the faces with a corner in the
// range), with each corner's position (or `none` where it adds nothing),
// then summed by position ranges at once, each in face order: every range's
// task reads the block's positions, 4 bytes a corner. On one thread, face
// by face without the block.
void sum_range(const std::vector<float>& vertices, const ObjFaces& faces, size_t lo, size_t hi,
               std::vector<vec3>& sums) {
  constexpr uint32_t none = ~0u;
  const std::vector<tinyobj::index_t>& idx = faces.corners;
  const size_t face_count = faces.face_start.size();
  auto in_range = [&](size_t corner) {
    const size_t v = size_t(idx[corner].vertex_index);
    return v >= lo && v < hi;
  };
  const size_t ranges = size_t(tbb::this_task_arena::max_concurrency());
  if (ranges == 1) {
    // One thread: each face's corners added as they are weighed, in the same order.
    for (size_t f = 0; f < face_count; ++f) {
      const size_t s = faces.face_start[f];
      if (faces.face_corners[f] != 3 || !(in_range(s) || in_range(s + 1) || in_range(s + 2))) continue;
      vec3 weighted[3];
      uint8_t adds[3];
      angle_weighted_normals(idx, s, vertices, weighted, adds);
      for (int k = 0; k < 3; ++k)
        if (adds[k] && in_range(s + k)) sums[size_t(idx[s + k].vertex_index)] += weighted[k];
    }
    return;
  }
  constexpr size_t block = size_t(1) << 16;
  std::vector<vec3> weighted(3 * std::min(face_count, block));
  std::vector<uint32_t> position(weighted.size());  // per corner of the block: its position, or none
  for (size_t first = 0; first < face_count; first += block) {
    const size_t last = std::min(face_count, first + block);
    tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 1024), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t f = r.begin(); f < r.end(); ++f) {
        uint32_t* at = &position[3 * (f - first)];
        at[0] = at[1] = at[2] = none;
        const size_t s = faces.face_start[f];
        if (faces.face_corners[f] != 3 || !(in_range(s) || in_range(s + 1) || in_range(s + 2))) continue;
        uint8_t adds[3];
        angle_weighted_normals(idx, s, vertices, &weighted[3 * (f - first)], adds);
        for (int k = 0; k < 3; ++k)
          if (adds[k]) at[k] = uint32_t(idx[s + k].vertex_index);
      }
    });
    const size_t corners = 3 * (last - first);
    tbb::parallel_for(size_t(0), ranges, [&](size_t range) {
      const size_t rlo = lo + (hi - lo) * range / ranges, rhi = lo + (hi - lo) * (range + 1) / ranges;
      for (size_t c = 0; c < corners; ++c) {
        const size_t v = position[c];  // none is past every range
        if (v >= rlo && v < rhi) sums[v] += weighted[c];
      }
    });
  }
}

// Part p's positions: [begin(p), begin(p + 1)).
size_t range_begin(size_t positions, int part, int parts) { return positions * size_t(part) / size_t(parts); }

}  // namespace

std::vector<vec3> smooth_normal_sums(const std::vector<float>& vertices, const ObjFaces& faces,
                                     const WorkShare* share) {
  const size_t positions = vertices.size() / 3;
  std::vector<vec3> sums;
  if (!share || !share->shared()) {
    sums.assign(positions, vec3(0.f));
    sum_range(vertices, faces, 0, positions, sums);
    return sums;
  }
  // A part's bytes: 1 and its range's sums, or 0 and what it threw. Nothing
  // is thrown before the exchange: every part reaches it.
  const int parts = share->parts;
  const size_t lo = range_begin(positions, share->part, parts), hi = range_begin(positions, share->part + 1, parts);
  std::vector<std::byte> mine;
  try {
    sums.assign(positions, vec3(0.f));
    sum_range(vertices, faces, lo, hi, sums);
    mine.resize(1 + (hi - lo) * sizeof(vec3));
    mine[0] = std::byte{1};
    if (hi > lo) std::memcpy(mine.data() + 1, sums.data() + lo, (hi - lo) * sizeof(vec3));
  } catch (...) {
    const std::string what = current_exception_message();
    mine.assign(1 + what.size(), std::byte{0});
    std::memcpy(mine.data() + 1, what.data(), what.size());
  }
  const std::vector<std::vector<std::byte>> all = share->exchange(std::move(mine));
  if (all.size() != size_t(parts))
    throw Error("shared smooth normals: " + std::to_string(all.size()) + " parts answered, not " +
                std::to_string(parts) + " (a bug)");
  for (int p = 0; p < parts; ++p)
    if (all[p].empty() || all[p][0] != std::byte{1})
      throw Error("generating smooth normals: part " + std::to_string(p) + " failed" +
                  (all[p].size() > 1
                       ? ": " + std::string(reinterpret_cast<const char*>(all[p].data()) + 1, all[p].size() - 1)
                       : std::string()));
  for (int p = 0; p < parts; ++p) {
    const size_t b = range_begin(positions, p, parts), e = range_begin(positions, p + 1, parts);
    if (all[p].size() != 1 + (e - b) * sizeof(vec3))
      throw Error("shared smooth normals: part " + std::to_string(p) + " sent " + std::to_string(all[p].size()) +
                  " bytes, not " + std::to_string(1 + (e - b) * sizeof(vec3)) + " (a bug)");
    if (p != share->part && e > b) std::memcpy(sums.data() + b, all[p].data() + 1, (e - b) * sizeof(vec3));
  }
  return sums;
}

}  // namespace rayform::obj
