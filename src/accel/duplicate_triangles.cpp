#include "rayform/accel/duplicate_triangles.h"

#include "rayform/base/select_in_order.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstring>
#include <span>

namespace rayform {
namespace {

// A 64-bit mix (splitmix64's finaliser) of h and the next 32 bits.
uint64_t mix(uint64_t h, uint32_t bits) {
  h ^= bits;
  h += 0x9e3779b97f4a7c15ull;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

template <typename T>
uint64_t mix_value(uint64_t h, const T& v) {
  static_assert(sizeof(T) % 4 == 0);
  uint32_t words[sizeof(T) / 4];
  std::memcpy(words, &v, sizeof(T));
  for (uint32_t w : words) h = mix(h, w);
  return h;
}

// The per-vertex arrays a hit reads, each compared only where it holds the vertex.
template <typename T>
bool same_at(const std::vector<T>& a, uint32_t i, uint32_t j) {
  if (a.size() <= i || a.size() <= j) return a.size() <= i && a.size() <= j;
  return std::memcmp(&a[i], &a[j], sizeof(T)) == 0;
}

template <typename T>
uint64_t mix_at(uint64_t h, const std::vector<T>& a, uint32_t i) {
  return a.size() > i ? mix_value(h, a[i]) : mix(h, 0xffffffffu);
}

// A cheap hash of a triangle's corner positions (9 words): the sort key of
// every triangle, so it is kept short.
uint64_t position_hash(const Mesh& m, size_t t) {
  uint64_t h = 0;
  for (size_t k = 0; k < 3; ++k) {
    uint32_t words[3];
    std::memcpy(words, &m.positions[m.indices[3 * t + k]], sizeof words);
    for (uint32_t w : words) {
      h = (h ^ w) * 0x9e3779b97f4a7c15ull;
      h ^= h >> 29;
    }
  }
  return h;
}

// Triangles a group of one position hash holds beyond which they are told
// apart by a hash of everything compared (a file of copies whose uvs differ
// would otherwise compare each with every distinct one).
constexpr size_t refine_group_size = 64;

}  // namespace

std::vector<uint32_t> distinct_triangles(const Mesh& m) {
  const size_t n = m.triangle_count();
  // Keys hold the index in their low 31 bits (larger meshes are refused by the build).
  constexpr int index_bits = 31;
  if (n < 2 || n >= (size_t(1) << index_bits)) return {};
  auto corner = [&](size_t t, size_t k) { return m.indices[3 * t + k]; };
  auto face_material = [&](size_t t) { return t < m.face_materials.size() ? m.face_materials[t] : invalid; };
  std::vector<uint64_t> hashes(n);
  tbb::parallel_for(size_t(0), n, [&](size_t t) { hashes[t] = position_hash(m, t); });
  // The candidates: triangles whose hash falls in a slot of a table of 8 to
  // 16 slots a triangle that another one's hash falls in too (every
  // duplicate, and about one triangle in 8 besides), so that only they are
  // sorted.
  const int slot_bits = int(std::bit_width(n)) + 3;
  const size_t words = (size_t(1) << slot_bits) / 64 + 1;
  std::vector<std::atomic<uint64_t>> seen(words), twice(words);  // zeroed (C++20)
  auto slot = [&](size_t t) { return hashes[t] >> (64 - slot_bits); };
  tbb::parallel_for(size_t(0), n, [&](size_t t) {
    const uint64_t s = slot(t), bit = uint64_t(1) << (s & 63);
    if (seen[s >> 6].fetch_or(bit, std::memory_order_relaxed) & bit)
      twice[s >> 6].fetch_or(bit, std::memory_order_relaxed);
  });
  std::vector<std::atomic<uint64_t>>().swap(seen);
  // (position hash, index) in one word, sorted: the candidates of equal
  // corner positions (and a few others) in runs, lowest index first.
  std::vector<uint64_t> keys;
  select_in_order(
      n, size_t(1) << 16,
      [&](size_t t) {
        const uint64_t s = slot(t);
        return (twice[s >> 6].load(std::memory_order_relaxed) >> (s & 63) & 1) != 0;
      },
      [&](size_t total) { keys.resize(total); }, [&](size_t t, size_t k) { keys[k] = (hashes[t] << index_bits) | t; });
  std::vector<std::atomic<uint64_t>>().swap(twice);
  std::vector<uint64_t>().swap(hashes);
  tbb::parallel_sort(keys.begin(), keys.end());
  const size_t candidates = keys.size();
  constexpr uint64_t index_mask = (uint64_t(1) << index_bits) - 1;
  auto full_hash = [&](size_t t) {
    uint64_t h = mix(0, uint32_t(face_material(t)));
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = corner(t, k);
      h = mix_at(h, m.positions, v);
      h = mix_at(h, m.normals, v);
      h = mix_at(h, m.uvs, v);
      h = mix_at(h, m.uvs1, v);
      h = mix_at(h, m.tangents, v);
      h = mix_at(h, m.colors, v);
    }
    return h;
  };
  auto same = [&](size_t s, size_t t) {
    if (face_material(s) != face_material(t)) return false;
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = corner(s, k), b = corner(t, k);
      if (a == b) continue;
      if (!same_at(m.positions, a, b) || !same_at(m.normals, a, b) || !same_at(m.uvs, a, b) || !same_at(m.uvs1, a, b) ||
          !same_at(m.tangents, a, b) || !same_at(m.colors, a, b))
        return false;
    }
    return true;
  };
  std::vector<uint8_t> merged(n, 0);
  bool any = false;
  std::vector<uint32_t> kept;  // the distinct triangles of one run, lowest first
  // Marks the duplicates among `run` (ascending indices).
  auto merge_run = [&](const uint32_t* run, size_t count) {
    kept.clear();
    for (size_t i = 0; i < count; ++i) {
      const uint32_t t = run[i];
      if (std::any_of(kept.begin(), kept.end(), [&](uint32_t s) { return same(s, t); })) {
        merged[t] = 1;
        any = true;
      } else {
        kept.push_back(t);
      }
    }
  };
  std::vector<uint32_t> run;
  std::vector<std::pair<uint64_t, uint32_t>> refined;
  for (size_t g = 0; g < candidates;) {
    size_t end = g + 1;
    while (end < candidates && keys[end] >> index_bits == keys[g] >> index_bits) ++end;
    if (end - g > 1) {
      run.clear();
      for (size_t i = g; i < end; ++i) run.push_back(uint32_t(keys[i] & index_mask));
      if (run.size() <= refine_group_size) {
        merge_run(run.data(), run.size());
      } else {
        refined.resize(run.size());
        tbb::parallel_for(size_t(0), run.size(), [&](size_t i) { refined[i] = {full_hash(run[i]), run[i]}; });
        tbb::parallel_sort(refined.begin(), refined.end());
        for (size_t i = 0; i < refined.size();) {
          size_t j = i + 1;
          while (j < refined.size() && refined[j].first == refined[i].first) ++j;
          for (size_t k = i; k < j; ++k) run[k - i] = refined[k].second;
          merge_run(run.data(), j - i);
          i = j;
        }
      }
    }
    g = end;
  }
  if (!any) return {};
  std::vector<uint64_t>().swap(keys);
  std::vector<uint32_t> distinct;
  for (size_t t = 0; t < n; ++t)
    if (!merged[t]) distinct.push_back(uint32_t(t));
  return distinct;
}

MeshAccel build_mesh_accel_without_duplicates(const Mesh& mesh, const BvhBuildOptions& options,
                                              const WorkShare* share) {
  const std::vector<uint32_t> kept = distinct_triangles(mesh);
  if (kept.empty()) return build_mesh_accel(mesh.positions, mesh.indices, options, share);
  std::vector<uint32_t> indices(3 * kept.size());
  for (size_t i = 0; i < kept.size(); ++i)
    for (size_t k = 0; k < 3; ++k) indices[3 * i + k] = mesh.indices[3 * size_t(kept[i]) + k];
  MeshAccel accel = build_mesh_accel(mesh.positions, indices, options, share);
  // Back to the mesh's own indices (ascending, so the leaf order's ties keep their order).
  for (TrianglePacket& p : accel.packets)
    for (uint32_t& id : p.id) id = kept[id];
  for (uint32_t& t : accel.triangles) t = kept[t];
  return accel;
}

}  // namespace rayform
