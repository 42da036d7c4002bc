// An OBJ mesh's vertices from its triangle corners: one vertex per distinct
// corner key (position, uv, normal), numbered in the order the keys are first
// met in corner order, and each corner's vertex. That is exactly what one loop
// over the corners with a hash map of keys gives; here in parallel (oneTBB):
//   1. each position's first corner (an atomic minimum);
//   2. a corner whose key is its position's first corner's key takes that
//      corner's vertex (most do: a position has one key but at uv seams and
//      creases); the others look their key up in a map, one after another in
//      corner order (so the first corner with each key still comes first),
//      the one thread visiting only the stretches that hold such corners;
//   3. the corners that come first with their key, numbered in corner order
//      (base/select_in_order.h), number the vertices.
#pragma once

#include "rayform/base/populate_pages.h"
#include "rayform/base/select_in_order.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rayform::obj {

// A corner's key. uv and normal are indices into the file's arrays, -1 for
// none; the caller may give a normal key below -1 of its own (a faceted
// corner: one per face).
struct CornerKey {
  int position = 0, uv = -1, normal = -1;
  bool operator==(const CornerKey&) const = default;
};

struct CornerKeyHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = uint64_t(uint32_t(k.position)) * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t(uint32_t(k.uv)) + 0x7F4A7C15ull + (h << 6) + (h >> 2));
    h ^= (uint64_t(uint32_t(k.normal)) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2));
    return size_t(h);
  }
};

struct WeldedVertices {
  std::vector<uint32_t> first_corner;   // per vertex: the first corner with its key
  std::vector<uint32_t> corner_vertex;  // per corner: its vertex
};

// `key_of(c)` gives corner c's key (0 <= c < corners, 0 <= position <
// positions); called from several threads at once.
template <class KeyOf>
WeldedVertices weld_vertices(size_t positions, size_t corners, const KeyOf& key_of) {
  constexpr uint32_t none = ~0u;
  constexpr size_t grain = size_t(1) << 14;
  const auto each_block = [&](size_t n, const auto& body) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                      [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
  };
  // 1. Each position's first corner.
  std::vector<uint32_t> first_at(positions, none);
  each_block(corners, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) {
      std::atomic_ref<uint32_t> first(first_at[size_t(key_of(c).position)]);
      uint32_t seen = first.load(std::memory_order_relaxed);
      while (uint32_t(c) < seen && !first.compare_exchange_weak(seen, uint32_t(c), std::memory_order_relaxed)) {
      }
    }
  });
  // 2. Each corner's representative: the first corner with its key (itself
  // when it is that corner). Corners whose key is not their position's first
  // key are left for the map, in corner order.
  std::vector<uint32_t> representative;
  resize_on_present_pages(representative, corners);
  std::vector<uint8_t> left_in((corners + grain - 1) / grain, 0);  // per grain of corners: any left for the map
  each_block(corners, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) {
      const CornerKey k = key_of(c);
      const uint32_t f = first_at[size_t(k.position)];
      representative[c] = f == c || key_of(f) == k ? f : none;
      if (representative[c] == none) std::atomic_ref<uint8_t>(left_in[c / grain]).store(1, std::memory_order_relaxed);
    }
  });
  std::unordered_map<CornerKey, uint32_t, CornerKeyHash> other_keys;
  for (size_t g = 0; g < left_in.size(); ++g) {
    if (!left_in[g]) continue;  // nothing to look up there
    for (size_t c = g * grain; c < std::min(corners, (g + 1) * grain); ++c)
      if (representative[c] == none) representative[c] = other_keys.try_emplace(key_of(c), uint32_t(c)).first->second;
  }
  // 3. Vertex numbers: corners that are their own representative, numbered
  // in corner order.
  WeldedVertices w;
  resize_on_present_pages(w.corner_vertex, corners);
  select_in_order(
      corners, grain, [&](size_t c) { return representative[c] == c; },
      [&](size_t total) { resize_on_present_pages(w.first_corner, total); },
      [&](size_t c, size_t v) {
        w.first_corner[v] = uint32_t(c);
        w.corner_vertex[c] = uint32_t(v);
      });
  each_block(corners, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c)
      if (representative[c] != c) w.corner_vertex[c] = w.corner_vertex[representative[c]];
  });
  return w;
}

}  // namespace rayform::obj
