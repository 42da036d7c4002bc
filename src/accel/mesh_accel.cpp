#include "accel/mesh_accel.h"

#include "accel/simd4.h"

#if RAYFORM_SIMD4_SSE
#include <immintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <deque>
#include <optional>
#include <cstdlib>
#include <stdexcept>

namespace rayform {
namespace {

using simd::f4;
using simd::m4;

// ============================================================== build

// A triangle's box, 32 bytes: lanes 0..2 of lo/hi are the box, lane 3 of lo
// holds the triangle id (its bits), lane 3 of hi is unused.
struct alignas(16) PrimRef {
  float lo[4];
  float hi[4];
  uint32_t id() const { return std::bit_cast<uint32_t>(lo[3]); }
};
static_assert(sizeof(PrimRef) == 32);

// Box in SIMD registers; lane 3 is ignored.
struct Box {
  f4 lo = simd::splat(infinity), hi = simd::splat(-infinity);
  void expand(f4 l, f4 h) { lo = simd::vmin(lo, l); hi = simd::vmax(hi, h); }
  void expand(const Box& b) { expand(b.lo, b.hi); }
  // Half the surface area; 0 for an empty box.
  float half_area() const { return simd::half_area(lo, hi); }
};

// Items [begin, end) of the PrimRef array with their box and the box of their
// doubled centroids (lo + hi, which saves a multiply per primitive).
struct Range {
  uint32_t begin = 0, end = 0;
  Box geom, cent;
  uint32_t count() const { return end - begin; }
};

// Adds a primitive's box and doubled centroid to r's boxes (not to its items).
inline void add(Range& r, const PrimRef& p) {
  f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
  r.geom.expand(lo, hi);
  f4 c = lo + hi;
  r.cent.expand(c, c);
}

constexpr int max_bins = 64;

struct Split {
  int axis = -1;  // -1: no SAH split (split by count)
  int nb = 0;     // bins per axis
  int pos = 0;    // primitives in bins <= pos go left
  float cost = infinity;  // SAH cost relative to a packet test
  float lo = 0.f, scale = 0.f;  // bin = (c - lo) * scale on `axis`
};

// Per axis and bin: the box of the primitives whose centroid falls in it, and
// their count. Only the first `nb` bins of each axis are used (and cleared).
struct Bins {
  f4 lo[3][max_bins], hi[3][max_bins];
  uint32_t count[3][max_bins];
  void clear(int nb) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < nb; ++b) {
        lo[a][b] = simd::splat(infinity);
        hi[a][b] = simd::splat(-infinity);
        count[a][b] = 0;
      }
  }
  void merge(const Bins& o, int nb) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < nb; ++b) {
        lo[a][b] = simd::vmin(lo[a][b], o.lo[a][b]);
        hi[a][b] = simd::vmax(hi[a][b], o.hi[a][b]);
        count[a][b] += o.count[a][b];
      }
  }
};

inline uint32_t blocks(uint32_t n) { return (n + 3) >> 2; }

struct BuildNode;

struct BuildChild {
  float lo[3], hi[3];
  BuildNode* node = nullptr;  // nullptr: a leaf of items [begin, end)
  uint32_t begin = 0, end = 0;
};

constexpr int W = WideBvhNode::width;

struct BuildNode {
  BuildChild child[W];
  int n = 0;
  // Totals of the subtree (this node included), for the flattening offsets.
  uint32_t nodes = 0, packets = 0, triangles = 0;
};

class MeshBuilder {
 public:
  MeshBuilder(std::vector<PrimRef>& refs, const BvhBuildOptions& o) : refs_(refs) {
    nb_ = std::clamp(o.bins, 2, max_bins);
    max_leaf_ = std::clamp(o.max_leaf_size, 1, int(4 * WideBvhNode::max_leaf_packets));
    min_leaf_ = std::min(4, max_leaf_);
    traversal_cost_ = std::max(0.f, o.traversal_cost);
  }

  // The root node (always a node, even over a single leaf).
  BuildNode* build(const Range& root) {
    if (root.count() <= uint32_t(max_leaf_)) {
      BuildNode* n = new_node();
      n->n = 1;
      n->child[0] = leaf(root);
      finish(n);
      return n;
    }
    Split s = find_split(root, 0);
    return build_node(root, s, 0);
  }

 private:
  static constexpr uint32_t parallel_threshold = 4096;   // smaller subtrees are built by one task
  static constexpr uint32_t parallel_bin_threshold = 1u << 15;
  // Beyond this depth, splits by count (each child at most half) keep the
  // tree within sah_depth_limit + 33 levels, which bounds the traversal stack.
  static constexpr int sah_depth_limit = 32;

  std::vector<PrimRef>& refs_;
  int nb_, max_leaf_, min_leaf_;
  float traversal_cost_;
  tbb::enumerable_thread_specific<std::deque<BuildNode>> arenas_;

  BuildNode* new_node() { return &arenas_.local().emplace_back(); }

  static void set_bounds(BuildChild& c, const Box& b) {
    float l[4], h[4];
    simd::store(l, b.lo);
    simd::store(h, b.hi);
    for (int a = 0; a < 3; ++a) { c.lo[a] = l[a]; c.hi[a] = h[a]; }
  }

  BuildChild leaf(const Range& r) const {
    BuildChild c;
    set_bounds(c, r.geom);
    c.begin = r.begin;
    c.end = r.end;
    return c;
  }

  void finish(BuildNode* n) const {
    n->nodes = 1;
    n->packets = 0;
    n->triangles = 0;
    for (int i = 0; i < n->n; ++i) {
      const BuildChild& c = n->child[i];
      if (c.node) {
        n->nodes += c.node->nodes;
        n->packets += c.node->packets;
        n->triangles += c.node->triangles;
      } else {
        n->packets += blocks(c.end - c.begin);
        n->triangles += c.end - c.begin;
      }
    }
  }

  // The bin of a doubled centroid coordinate; the same float operations for
  // binning and partitioning.
  static int bin_of(float c, float lo, float scale, int nb) {
    float x = (c - lo) * scale;
    int b = int(x);
    return x >= 0.f ? std::min(b, nb - 1) : 0;
  }

  void bin_range(uint32_t begin, uint32_t end, const f4& clo, const f4& scale, int nb, Bins& bins) const {
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& p = refs_[i];
      f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
      int b[4];
      simd::to_int_clamped((lo + hi - clo) * scale, nb - 1, b);
      for (int a = 0; a < 3; ++a) {
        bins.lo[a][b[a]] = simd::vmin(bins.lo[a][b[a]], lo);
        bins.hi[a][b[a]] = simd::vmax(bins.hi[a][b[a]], hi);
        bins.count[a][b[a]]++;
      }
    }
  }

  Split find_split(const Range& r, int depth) const {
    Split best;
    if (depth > sah_depth_limit) return best;
    float clo[4], chi[4], scale[4] = {0.f, 0.f, 0.f, 0.f};
    simd::store(clo, r.cent.lo);
    simd::store(chi, r.cent.hi);
    // Fewer bins for few primitives (the sweep costs as much as the binning there).
    const int nb = std::min(nb_, std::max(4, int(r.count() / 2)));
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      float ext = chi[a] - clo[a];
      if (ext > 0.f && std::isfinite(ext)) {
        scale[a] = float(nb) * (1.f - 1e-6f) / ext;
        any = true;
      }
    }
    if (!any) return best;
    const f4 vlo = simd::loadu(clo), vscale = simd::loadu(scale);
    Bins bins;
    bins.clear(nb);
    if (r.count() >= parallel_bin_threshold) {
      bins = tbb::parallel_reduce(
          tbb::blocked_range<uint32_t>(r.begin, r.end, 1u << 13), bins,
          [&](const tbb::blocked_range<uint32_t>& br, Bins acc) {
            bin_range(br.begin(), br.end(), vlo, vscale, nb, acc);
            return acc;
          },
          [&](Bins a, const Bins& b) {
            a.merge(b, nb);
            return a;
          });
    } else {
      bin_range(r.begin, r.end, vlo, vscale, nb, bins);
    }
    for (int a = 0; a < 3; ++a) {
      if (scale[a] == 0.f) continue;
      float right_area[max_bins];
      uint32_t right_count[max_bins];
      Box acc;
      uint32_t n = 0;
      for (int i = nb - 1; i > 0; --i) {
        acc.expand(bins.lo[a][i], bins.hi[a][i]);
        n += bins.count[a][i];
        right_area[i] = acc.half_area();
        right_count[i] = n;
      }
      acc = Box{};
      n = 0;
      for (int i = 0; i < nb - 1; ++i) {
        acc.expand(bins.lo[a][i], bins.hi[a][i]);
        n += bins.count[a][i];
        if (n == 0 || right_count[i + 1] == 0) continue;
        float cost = acc.half_area() * float(blocks(n)) + right_area[i + 1] * float(blocks(right_count[i + 1]));
        if (cost < best.cost) {
          best.cost = cost;
          best.axis = a;
          best.nb = nb;
          best.pos = i;
          best.lo = clo[a];
          best.scale = scale[a];
        }
      }
    }
    if (best.axis >= 0) {
      float area = r.geom.half_area();
      best.cost = traversal_cost_ + (area > 0.f ? best.cost / area : 0.f);
    }
    return best;
  }

  // Splits r by s (or, without a SAH split, by count) into two non-empty ranges.
  std::pair<Range, Range> partition(const Range& r, const Split& s) {
    Range left, right;
    uint32_t mid = r.begin;
    if (s.axis >= 0) {
      const int axis = s.axis;
      auto goes_left = [&](const PrimRef& p) { return bin_of(p.lo[axis] + p.hi[axis], s.lo, s.scale, s.nb) <= s.pos; };
      uint32_t i = r.begin, j = r.end;
      for (;;) {
        while (i < j && goes_left(refs_[i])) add(left, refs_[i++]);
        while (i < j && !goes_left(refs_[j - 1])) add(right, refs_[--j]);
        if (i >= j) break;
        std::swap(refs_[i], refs_[j - 1]);
      }
      mid = i;
    }
    if (s.axis < 0 || mid == r.begin || mid == r.end) {
      // By count, at the median of the widest centroid axis when there is one.
      mid = r.begin + r.count() / 2;
      float clo[4], chi[4];
      simd::store(clo, r.cent.lo);
      simd::store(chi, r.cent.hi);
      int axis = 0;
      for (int a = 1; a < 3; ++a)
        if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
      if (chi[axis] > clo[axis])
        std::nth_element(refs_.begin() + r.begin, refs_.begin() + mid, refs_.begin() + r.end,
                         [axis](const PrimRef& a, const PrimRef& b) {
                           float ca = a.lo[axis] + a.hi[axis], cb = b.lo[axis] + b.hi[axis];
                           return ca < cb || (ca == cb && a.id() < b.id());
                         });
      left = Range{};
      right = Range{};
      for (uint32_t i = r.begin; i < mid; ++i) add(left, refs_[i]);
      for (uint32_t i = mid; i < r.end; ++i) add(right, refs_[i]);
    }
    left.begin = r.begin;
    left.end = mid;
    right.begin = mid;
    right.end = r.end;
    return {left, right};
  }

  // A child for range r: a leaf, or a node built below it.
  BuildChild make_child(const Range& r, int depth) {
    if (r.count() <= uint32_t(min_leaf_)) return leaf(r);
    Split s = find_split(r, depth);
    if (r.count() <= uint32_t(max_leaf_) && float(blocks(r.count())) <= s.cost) return leaf(r);
    BuildChild c;
    set_bounds(c, r.geom);
    c.node = build_node(r, s, depth);
    return c;
  }

  // Opens r into up to W ranges, splitting the one of largest area each
  // time, then builds below each.
  BuildNode* build_node(const Range& r, const Split& s, int depth) {
    Range cr[W];
    std::optional<Split> cs[W];
    cr[0] = r;
    cs[0] = s;
    int k = 1;
    while (k < W) {
      int best = -1;
      float best_area = -1.f;
      for (int i = 0; i < k; ++i) {
        if (cr[i].count() <= uint32_t(min_leaf_)) continue;
        float a = cr[i].geom.half_area();
        if (a > best_area) { best_area = a; best = i; }
      }
      if (best < 0) break;
      if (!cs[best]) cs[best] = find_split(cr[best], depth);
      auto [l, rr] = partition(cr[best], *cs[best]);
      cr[best] = l;
      cs[best].reset();
      cr[k] = rr;
      cs[k].reset();
      ++k;
    }
    BuildNode* n = new_node();
    n->n = k;
    if (r.count() >= parallel_threshold) {
      tbb::parallel_for(0, k, [&](int i) { n->child[i] = make_child(cr[i], depth + 1); });
    } else {
      for (int i = 0; i < k; ++i) n->child[i] = make_child(cr[i], depth + 1);
    }
    finish(n);
    return n;
  }
};

// Writes the build tree depth first: a node, the packets of its leaf children,
// then its interior children's subtrees in order. Offsets come from the
// subtree totals, so subtrees are written in parallel and the result does not
// depend on the threads.
struct Flattener {
  const std::vector<PrimRef>& refs;
  std::span<const vec3> positions;
  std::span<const uint32_t> indices;
  MeshAccel& out;

  void write_leaf(uint32_t begin, uint32_t end, uint32_t packet, uint32_t tri) {
    uint32_t n = end - begin;
    for (uint32_t i = 0; i < n; ++i) out.triangles[tri + i] = refs[begin + i].id();
    for (uint32_t k = 0; k < blocks(n); ++k) {
      TrianglePacket& p = out.packets[packet + k];
      for (uint32_t lane = 0; lane < 4; ++lane) {
        uint32_t item = std::min(begin + 4 * k + lane, end - 1);  // unused lanes repeat the last triangle
        uint32_t t = refs[item].id();
        p.id[lane] = t;
        for (int v = 0; v < 3; ++v) {
          const vec3& q = positions[indices[3 * size_t(t) + v]];
          for (int a = 0; a < 3; ++a) p.v[3 * v + a][lane] = q[a];
        }
      }
    }
  }

  void write(const BuildNode* bn, uint32_t index, uint32_t packet, uint32_t tri) {
    WideBvhNode& o = out.bvh.nodes[index];
    uint32_t next_node = index + 1;
    struct Task { const BuildNode* node; uint32_t index, packet, tri; };
    Task tasks[W];
    int ntasks = 0;
    for (int i = 0; i < W; ++i) {
      if (i >= bn->n) {
        for (int a = 0; a < 3; ++a) {
          o.bounds[2 * a][i] = infinity;
          o.bounds[2 * a + 1][i] = -infinity;
        }
        o.child[i] = WideBvhNode::leaf_ref(0, 0);
        continue;
      }
      const BuildChild& c = bn->child[i];
      for (int a = 0; a < 3; ++a) {
        o.bounds[2 * a][i] = c.lo[a];
        o.bounds[2 * a + 1][i] = c.hi[a];
      }
      if (!c.node) {
        uint32_t np = blocks(c.end - c.begin);
        o.child[i] = WideBvhNode::leaf_ref(packet, np);
        write_leaf(c.begin, c.end, packet, tri);
        packet += np;
        tri += c.end - c.begin;
      }
    }
    for (int i = 0; i < bn->n; ++i) {
      const BuildChild& c = bn->child[i];
      if (!c.node) continue;
      o.child[i] = next_node;
      tasks[ntasks++] = {c.node, next_node, packet, tri};
      next_node += c.node->nodes;
      packet += c.node->packets;
      tri += c.node->triangles;
    }
    for (uint32_t& p : o.pad) p = 0;
    if (bn->triangles >= 8192 && ntasks > 1) {
      tbb::parallel_for(0, ntasks, [&](int t) { write(tasks[t].node, tasks[t].index, tasks[t].packet, tasks[t].tri); });
    } else {
      for (int t = 0; t < ntasks; ++t) write(tasks[t].node, tasks[t].index, tasks[t].packet, tasks[t].tri);
    }
  }
};

}  // namespace

MeshAccel build_mesh_accel(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           const BvhBuildOptions& options) {
  MeshAccel m;
  const size_t n = indices.size() / 3;
  if (n >= (size_t(1) << 31)) throw std::length_error("build_mesh_accel: too many triangles");

  // Triangle boxes; those with empty or non-finite bounds are left out.
  std::vector<PrimRef> refs(n);
  size_t valid = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 1u << 14), size_t(0),
      [&](const tbb::blocked_range<size_t>& r, size_t count) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          Bounds3 b;
          for (int k = 0; k < 3; ++k) b.expand(positions[indices[3 * i + k]]);
          bool ok = !b.empty() && is_finite(b.lo) && is_finite(b.hi);
          PrimRef& p = refs[i];
          for (int a = 0; a < 3; ++a) { p.lo[a] = b.lo[a]; p.hi[a] = b.hi[a]; }
          p.lo[3] = std::bit_cast<float>(uint32_t(i));
          p.hi[3] = ok ? 1.f : 0.f;
          count += ok;
        }
        return count;
      },
      [](size_t a, size_t b) { return a + b; });
  if (valid != n) {
    refs.erase(std::remove_if(refs.begin(), refs.end(), [](const PrimRef& p) { return p.hi[3] == 0.f; }), refs.end());
  }
  if (refs.empty()) return m;

  Range root = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, refs.size(), 1u << 14), Range{},
      [&](const tbb::blocked_range<size_t>& r, Range acc) {
        for (size_t i = r.begin(); i < r.end(); ++i) add(acc, refs[i]);
        return acc;
      },
      [](Range a, const Range& b) {
        a.geom.expand(b.geom);
        a.cent.expand(b.cent);
        return a;
      });
  root.end = uint32_t(refs.size());

  MeshBuilder builder(refs, options);
  const BuildNode* tree = builder.build(root);
  if (tree->packets >= (1u << (31 - WideBvhNode::count_bits)))
    throw std::length_error("build_mesh_accel: too many triangle packets");

  m.bvh.nodes.resize(tree->nodes);
  m.packets.resize(tree->packets);
  m.triangles.resize(tree->triangles);
  Flattener{refs, positions, indices, m}.write(tree, 0, 0, 0);
  float l[4], h[4];
  simd::store(l, root.geom.lo);
  simd::store(h, root.geom.hi);
  m.bvh.root_bounds = Bounds3{vec3(l[0], l[1], l[2]), vec3(h[0], h[1], h[2])};
  return m;
}

// ============================================================== traversal

namespace {

// Per-ray constants of the watertight triangle test (make_triangle_ray), for
// four triangles at a time: the permutation as packet rows, the shear, the
// permuted origin.
struct TriRay {
  int kx, ky, kz;
  f4 okx, oky, okz, sx, sy, sz;
  float tmin;

  explicit TriRay(const Ray& ray) {
    const TriangleRay tr = make_triangle_ray(ray);
    kx = tr.kx; ky = tr.ky; kz = tr.kz;
    okx = simd::splat(tr.origin[kx]);
    oky = simd::splat(tr.origin[ky]);
    okz = simd::splat(tr.origin[kz]);
    sx = simd::splat(tr.sx);
    sy = simd::splat(tr.sy);
    sz = simd::splat(tr.sz);
    tmin = ray.tmin;
  }
};

// Results of the watertight test on one packet (valid lanes in `mask`).
struct PacketHits {
  int mask = 0;
  f4 t, e0, e1, e2, inv_det;
};

// intersect_triangle of geometry/triangle_intersect.h on four triangles: the
// same float operations in the same order, lane by lane, so the same hits and
// the same values (bvh_test checks this bit for bit against the scalar test).
// Keep the two in step. One difference: `front` below accepts a lane whose
// vertices all lie in front by more than their z error without the t bound,
// which the scalar test always applies (and which rejects hits on extreme
// slivers, e.g. 2000 x 2e-7 at distance 1, that this test keeps).
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline PacketHits intersect_packet(const TrianglePacket& p, const TriRay& r, float tmax) {
  using namespace simd;
  PacketHits h;
  // Vertices relative to the origin, permuted (rows kx, ky, kz of each vertex), sheared.
  f4 ax = load(p.v[0 + r.kx]) - r.okx, ay = load(p.v[0 + r.ky]) - r.oky, az = load(p.v[0 + r.kz]) - r.okz;
  f4 bx = load(p.v[3 + r.kx]) - r.okx, by = load(p.v[3 + r.ky]) - r.oky, bz = load(p.v[3 + r.kz]) - r.okz;
  f4 cx = load(p.v[6 + r.kx]) - r.okx, cy = load(p.v[6 + r.ky]) - r.oky, cz = load(p.v[6 + r.kz]) - r.okz;
  ax = ax + r.sx * az; ay = ay + r.sy * az;
  bx = bx + r.sx * bz; by = by + r.sy * bz;
  cx = cx + r.sx * cz; cy = cy + r.sy * cz;

  f4 e0 = bx * cy - by * cx;
  f4 e1 = cx * ay - cy * ax;
  f4 e2 = ax * by - ay * bx;
  const f4 zero = splat(0.f);
  int zero_lanes = mask_bits((e0 == zero) | (e1 == zero) | (e2 == zero));
  if (zero_lanes) {
    // An edge function rounded to zero: that lane's three are redone in double.
    alignas(16) float axs[4], ays[4], bxs[4], bys[4], cxs[4], cys[4], e0s[4], e1s[4], e2s[4];
    store(axs, ax); store(ays, ay); store(bxs, bx); store(bys, by); store(cxs, cx); store(cys, cy);
    store(e0s, e0); store(e1s, e1); store(e2s, e2);
    for (int i = 0; i < 4; ++i) {
      if (!(zero_lanes >> i & 1)) continue;
      e0s[i] = float(double(bxs[i]) * double(cys[i]) - double(bys[i]) * double(cxs[i]));
      e1s[i] = float(double(cxs[i]) * double(ays[i]) - double(cys[i]) * double(axs[i]));
      e2s[i] = float(double(axs[i]) * double(bys[i]) - double(ays[i]) * double(bxs[i]));
    }
    e0 = load(e0s); e1 = load(e1s); e2 = load(e2s);
  }
  m4 has_neg = (e0 < zero) | (e1 < zero) | (e2 < zero);
  m4 has_pos = (e0 > zero) | (e1 > zero) | (e2 > zero);
  f4 det = e0 + e1 + e2;
  m4 valid = ~((has_neg & has_pos) | (det == zero));
  if (mask_bits(valid) == 0) return h;

  // std::max({a, b, c}) keeps the first of equal maxima, as vmax(next, current)
  // does; std::min({a, b, c}) likewise with vmin(next, current).
  const f4 max_z = vmax(vabs(cz), vmax(vabs(bz), vabs(az)));
  az = az * r.sz; bz = bz * r.sz; cz = cz * r.sz;
  f4 t_scaled = e0 * az + e1 * bz + e2 * cz;
  const f4 tmin4 = splat(r.tmin), tmax4 = splat(tmax);
  f4 tmin_det = tmin4 * det, tmax_det = tmax4 * det;
  m4 neg = det < zero, pos = det > zero;
  valid = andnot(valid, neg & ((t_scaled >= tmin_det) | (t_scaled <= tmax_det)));
  valid = andnot(valid, pos & ((t_scaled <= tmin_det) | (t_scaled >= tmax_det)));
  if (mask_bits(valid) == 0) return h;

  f4 inv_det = splat(1.f) / det;
  f4 t = t_scaled * inv_det;
  valid = valid & (t > tmin4) & (t < tmax4);

  // In front of the origin despite rounding: every vertex in front by more
  // than its z error, or else t above the conservative bound on its error.
  f4 max_zt = vmax(vabs(cz), vmax(vabs(bz), vabs(az)));
  f4 delta_z = splat(gamma_bound(3)) * max_zt;
  m4 front = vmin(cz, vmin(bz, az)) > delta_z;
  if (mask_bits(andnot(valid, front))) {
    f4 max_xt = vmax(vabs(cx), vmax(vabs(bx), vabs(ax)));
    f4 max_yt = vmax(vabs(cy), vmax(vabs(by), vabs(ay)));
    f4 delta_x = splat(gamma_bound(5)) * (max_xt + max_z);
    f4 delta_y = splat(gamma_bound(5)) * (max_yt + max_z);
    f4 delta_e = splat(2.f) * (splat(gamma_bound(2)) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    f4 max_e = vmax(vabs(e2), vmax(vabs(e1), vabs(e0)));
    f4 delta_t = splat(3.f) * (splat(gamma_bound(3)) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) *
                 vabs(inv_det);
    valid = valid & (front | (t > delta_t));
  }
  h.mask = mask_bits(valid);
  h.t = t;
  h.e0 = e0; h.e1 = e1; h.e2 = e2;
  h.inv_det = inv_det;
  return h;
}

// The slab test's far distances are scaled up by this (bounds.h, slab_hit).
constexpr float far_scale = 1.f + 2.f * gamma_bound(3);

// Deep enough for any tree the builder makes (at most 66 levels of nodes, see
// MeshBuilder::sah_depth_limit), each pushing at most width - 1 entries.
constexpr int stack_size = 66 * (WideBvhNode::width - 1) + 1;

// The index of mask's lowest set bit (mask != 0), which is cleared.
inline int pop_lowest_bit(int& mask) {
  const int i = std::countr_zero(unsigned(mask));
  mask &= mask - 1;
  return i;
}

// Asks for the memory of a child before it is visited (traversal is bound by
// cache misses on incoherent rays): a node's four cache lines, or the first
// packet of a leaf.
inline void prefetch_child(const WideBvhNode* nodes, const TrianglePacket* packets, uint32_t ref) {
#if defined(__GNUC__)
  const char* p;
  int lines;
  if (WideBvhNode::is_leaf(ref)) {
    p = reinterpret_cast<const char*>(packets + WideBvhNode::leaf_first_packet(ref));
    lines = 3;
  } else {
    p = reinterpret_cast<const char*>(nodes + ref);
    lines = 4;
  }
  for (int i = 0; i < lines; ++i) __builtin_prefetch(p + 64 * i);
#else
  (void)nodes; (void)packets; (void)ref;
#endif
}

// The octant of a ray's direction: bit a set when the slab test takes the
// far side first on axis a (make_ray_slabs' dir_is_neg). The kernels are
// instantiated per octant, so that the rows of the near and far planes are
// constants: bounds[near_row<Oct>(a)], bounds[far_row<Oct>(a)].
inline int octant(const RaySlabs& s) { return s.dir_is_neg[0] | s.dir_is_neg[1] << 1 | s.dir_is_neg[2] << 2; }
template <int Oct> constexpr int near_row(int a) { return 2 * a + ((Oct >> a) & 1); }
template <int Oct> constexpr int far_row(int a) { return 2 * a + 1 - ((Oct >> a) & 1); }

// Per-ray constants of the slab test, for the portable node test.
struct NodeRay4 {
  f4 org[3], inv[3];
  float tmin;
  NodeRay4(const RaySlabs& s, float ray_tmin) {
    for (int a = 0; a < 3; ++a) {
      org[a] = simd::splat(s.origin[a]);
      inv[a] = simd::splat(s.inv_dir[a]);
    }
    tmin = ray_tmin;
  }
};

}  // namespace

// The slab test of bounds.h (slab_hit) on the eight boxes of a node, as two
// halves of four: the same operations lane by lane (the far scale applied to
// the minimum of the far distances, which rounds the same as scaling each).
// Returns the mask of boxes hit and writes their entry distances.
namespace {
namespace kernel_portable {
using NodeRay = NodeRay4;
template <int Oct>
inline int node_hits(const WideBvhNode& n, const NodeRay& r, float tmax, float* t_enter) {
  int mask = 0;
  for (int half = 0; half < 2; ++half) {
    f4 t0 = simd::splat(r.tmin), t1 = simd::splat(infinity);
    for (int a = 0; a < 3; ++a) {
      f4 tn = (simd::load(&n.bounds[near_row<Oct>(a)][4 * half]) - r.org[a]) * r.inv[a];
      f4 tf = (simd::load(&n.bounds[far_row<Oct>(a)][4 * half]) - r.org[a]) * r.inv[a];
      t0 = simd::vmax(tn, t0);
      t1 = simd::vmin(tf, t1);
    }
    t1 = simd::vmin(t1 * simd::splat(far_scale), simd::splat(tmax));
    simd::store(t_enter + 4 * half, t0);
    mask |= simd::mask_bits(t0 <= t1) << (4 * half);
  }
  return mask;
}
#include "accel/mesh_accel_kernel.h"
}  // namespace kernel_portable
}  // namespace

#if RAYFORM_SIMD4_SSE && defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define RAYFORM_HAVE_AVX2_KERNEL 1
#pragma GCC push_options
#pragma GCC target("avx2")
namespace {
namespace kernel_avx2 {
struct NodeRay {
  __m256 org[3], inv[3];
  float tmin;
  NodeRay(const RaySlabs& s, float ray_tmin) {
    for (int a = 0; a < 3; ++a) {
      org[a] = _mm256_set1_ps(s.origin[a]);
      inv[a] = _mm256_set1_ps(s.inv_dir[a]);
    }
    tmin = ray_tmin;
  }
};
// As kernel_portable::node_hits, eight lanes at once (AVX: max/min/compare
// have the same lane semantics as their SSE forms).
template <int Oct>
inline int node_hits(const WideBvhNode& n, const NodeRay& r, float tmax, float* t_enter) {
  __m256 t0 = _mm256_set1_ps(r.tmin), t1 = _mm256_set1_ps(infinity);
  for (int a = 0; a < 3; ++a) {
    __m256 tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.bounds[near_row<Oct>(a)]), r.org[a]), r.inv[a]);
    __m256 tf = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.bounds[far_row<Oct>(a)]), r.org[a]), r.inv[a]);
    t0 = _mm256_max_ps(tn, t0);
    t1 = _mm256_min_ps(tf, t1);
  }
  t1 = _mm256_min_ps(_mm256_mul_ps(t1, _mm256_set1_ps(far_scale)), _mm256_set1_ps(tmax));
  _mm256_storeu_ps(t_enter, t0);
  return _mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}
#include "accel/mesh_accel_kernel.h"
}  // namespace kernel_avx2
}  // namespace
#pragma GCC pop_options
#endif

#if RAYFORM_HAVE_AVX2_KERNEL
namespace {
// AVX2 node tests when the CPU has them (RAYFORM_NO_AVX2=1 forces the portable path).
bool use_avx2() {
  static const bool avx2 = [] {
    const char* off = std::getenv("RAYFORM_NO_AVX2");
    return __builtin_cpu_supports("avx2") && !(off && *off && *off != '0');
  }();
  return avx2;
}
}  // namespace
#endif

bool intersect_mesh(const MeshAccel& m, const Ray& ray, float& tmax, MeshHit* hit) {
#if RAYFORM_HAVE_AVX2_KERNEL
  if (use_avx2()) return kernel_avx2::intersect(m, ray, tmax, hit);
#endif
  return kernel_portable::intersect(m, ray, tmax, hit);
}

bool occluded_mesh(const MeshAccel& m, const Ray& ray) {
#if RAYFORM_HAVE_AVX2_KERNEL
  if (use_avx2()) return kernel_avx2::occluded(m, ray);
#endif
  return kernel_portable::occluded(m, ray);
}

}  // namespace rayform
