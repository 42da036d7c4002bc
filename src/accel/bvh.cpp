#include "rayform/accel/bvh.h"

#include <algorithm>
#include <numeric>

namespace rayform {
namespace {

struct BuildItem {
  Bounds3 bounds;
  vec3 centroid;
  uint32_t id;
};

struct Builder {
  const BvhBuildOptions& options;
  std::vector<BuildItem>& items;
  Bvh& out;

  // Builds the subtree of items[begin, end) and returns its node index.
  uint32_t build(uint32_t begin, uint32_t end, int depth) {
    uint32_t index = uint32_t(out.nodes.size());
    out.nodes.push_back({});
    Bounds3 bounds, centroids;
    for (uint32_t i = begin; i < end; ++i) {
      bounds.expand(items[i].bounds);
      centroids.expand(items[i].centroid);
    }
    uint32_t count = end - begin;
    auto make_leaf = [&] {
      BvhNode& n = out.nodes[index];
      n.lo = bounds.lo;
      n.hi = bounds.hi;
      n.offset = uint32_t(out.primitives.size());
      n.count = uint16_t(count);
      for (uint32_t i = begin; i < end; ++i) out.primitives.push_back(items[i].id);
      return index;
    };
    if (count == 1) return make_leaf();

    int axis = max_dimension(centroids.extent());
    uint32_t mid = begin;
    if (centroids.hi[axis] == centroids.lo[axis] || depth >= bvh_max_depth - 32) {
      // All centroids coincide: no plane separates them; split by order.
      if (count <= uint32_t(options.max_leaf_size)) return make_leaf();
      mid = begin + count / 2;
    } else {
      // Binned SAH over the axis of widest centroid spread.
      const int nb = options.bins;
      struct Bin {
        Bounds3 b;
        uint32_t n = 0;
      };
      std::vector<Bin> bins(nb);
      float lo = centroids.lo[axis], scale = nb / (centroids.hi[axis] - lo);
      // A centroid that is not finite (an instance whose bounds overflowed)
      // goes to the first or last bin; a float outside int's range is not
      // converted (undefined behaviour).
      auto bin_of = [&](const BuildItem& it) {
        const float f = (it.centroid[axis] - lo) * scale;
        return f >= 0.f ? std::min(nb - 1, int(std::min(f, float(nb)))) : 0;
      };
      for (uint32_t i = begin; i < end; ++i) {
        Bin& b = bins[bin_of(items[i])];
        b.b.expand(items[i].bounds);
        b.n++;
      }
      // Sweep from the right to get the area of every right side.
      std::vector<float> right_area(nb);
      std::vector<uint32_t> right_count(nb);
      Bounds3 acc;
      uint32_t n = 0;
      for (int i = nb - 1; i > 0; --i) {
        acc.expand(bins[i].b);
        n += bins[i].n;
        right_area[i] = acc.surface_area();
        right_count[i] = n;
      }
      float best_cost = infinity;
      int best = -1;
      acc = {};
      n = 0;
      for (int i = 0; i < nb - 1; ++i) {
        acc.expand(bins[i].b);
        n += bins[i].n;
        if (n == 0 || right_count[i + 1] == 0) continue;
        float cost = n * acc.surface_area() + right_count[i + 1] * right_area[i + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best = i;
        }
      }
      float area = bounds.surface_area();
      float split_cost = options.traversal_cost + (area > 0.f ? best_cost / area : 0.f);
      if (count <= uint32_t(options.max_leaf_size) && (best < 0 || split_cost >= float(count))) return make_leaf();
      if (best < 0) {
        mid = begin + count / 2;
      } else {
        auto it = std::partition(items.begin() + begin, items.begin() + end,
                                 [&](const BuildItem& x) { return bin_of(x) <= best; });
        mid = uint32_t(it - items.begin());
        if (mid == begin || mid == end) mid = begin + count / 2;
      }
    }
    if (mid == begin + count / 2 && !(centroids.hi[axis] == centroids.lo[axis])) {
      std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                       [&](const BuildItem& a, const BuildItem& b) { return a.centroid[axis] < b.centroid[axis]; });
    }
    build(begin, mid, depth + 1);
    uint32_t right = build(mid, end, depth + 1);
    BvhNode& n = out.nodes[index];
    n.lo = bounds.lo;
    n.hi = bounds.hi;
    n.offset = right;
    n.count = 0;
    n.axis = uint8_t(axis);
    return index;
  }
};

}  // namespace

Bvh build_bvh(std::span<const Bounds3> primitive_bounds, const BvhBuildOptions& options) {
  std::vector<BuildItem> items;
  items.reserve(primitive_bounds.size());
  for (uint32_t i = 0; i < primitive_bounds.size(); ++i) {
    const Bounds3& b = primitive_bounds[i];
    if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi)) continue;
    items.push_back({b, b.center(), i});
  }
  Bvh bvh;
  if (items.empty()) return bvh;
  bvh.nodes.reserve(2 * items.size() / std::max(1, options.max_leaf_size / 2) + 1);
  bvh.primitives.reserve(items.size());
  Builder builder{options, items, bvh};
  builder.build(0, uint32_t(items.size()), 0);
  bvh.nodes.shrink_to_fit();
  return bvh;
}

}  // namespace rayform
