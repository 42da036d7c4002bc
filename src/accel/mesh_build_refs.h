// The input of the MeshAccel builder (mesh_accel_builder.h): a box per
// triangle (PrimRef), boxes held in SIMD registers, and ranges of the PrimRef
// array with their boxes; triangle_refs makes them for a mesh.
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/accel/simd4.h"
#include "rayform/base/populate_pages.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

namespace rayform::mesh_build {

using simd::f4;

// A triangle's box, 32 bytes: lanes 0..2 of lo/hi are the box, lane 3 of lo
// holds the triangle id (its bits), lane 3 of hi the bins of its last binning
// (see bin_bits).
struct alignas(16) PrimRef {
  float lo[4];
  float hi[4];
  uint32_t id() const { return std::bit_cast<uint32_t>(lo[3]); }
  // The bin on `axis` that find_split (mesh_build_split.h) last gave this primitive.
  uint32_t bin(int axis) const { return (std::bit_cast<uint32_t>(hi[3]) >> (bin_shift * axis)) & bin_mask; }

  static constexpr int bin_shift = 6;  // bits per axis; bins < 64
  static constexpr uint32_t bin_mask = (1u << bin_shift) - 1;
  // hi[3] for bins b0, b1, b2: their bits under the exponent of 1.0f, so that
  // lane 3 stays a normal float (denormals can be slow in the box arithmetic).
  static float bin_bits(uint32_t b0, uint32_t b1, uint32_t b2) {
    return std::bit_cast<float>(0x3f800000u | b0 | b1 << bin_shift | b2 << (2 * bin_shift));
  }
};
static_assert(sizeof(PrimRef) == 32);

// Box in SIMD registers; lane 3 is ignored.
struct Box {
  f4 lo = simd::splat(infinity), hi = simd::splat(-infinity);
  void expand(f4 l, f4 h) {
    lo = simd::vmin(lo, l);
    hi = simd::vmax(hi, h);
  }
  void expand(const Box& b) { expand(b.lo, b.hi); }
  // As expand, but where bounds tie (+0 and -0) the box keeps its own: the
  // result of expanding by l, h before the items already in the box.
  void expand_before(f4 l, f4 h) {
    lo = simd::vmin(l, lo);
    hi = simd::vmax(h, hi);
  }
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

// As add, but as if p were added before the primitives already in r's boxes.
inline void add_before(Range& r, const PrimRef& p) {
  f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
  r.geom.expand_before(lo, hi);
  f4 c = lo + hi;
  r.cent.expand_before(c, c);
}

// The packets of four triangles that n triangles fill.
inline uint32_t blocks(uint32_t n) { return (n + 3) >> 2; }

// The PrimRefs of the triangles with finite vertices, in index order, and
// the root range over them.
inline Range triangle_refs(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           std::vector<PrimRef>& refs) {
  const size_t n = indices.size() / 3;
  // Triangle boxes, and the root range's boxes; triangles with a non-finite
  // vertex are left out (a NaN vertex would not even reach the box: min and
  // max pass over it).
  struct Boxes {
    size_t valid = 0;  // triangles with a box
    Range root;        // over those, in index order
  };
  resize_on_present_pages(refs, n);
  Boxes boxes = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 1u << 14), Boxes{},
      [&](const tbb::blocked_range<size_t>& r, Boxes acc) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          Bounds3 b;
          bool ok = true;
          for (int k = 0; k < 3; ++k) {
            const vec3& v = positions[indices[3 * i + k]];
            b.expand(v);
            ok = ok && is_finite(v);
          }
          PrimRef& p = refs[i];
          for (int a = 0; a < 3; ++a) {
            p.lo[a] = b.lo[a];
            p.hi[a] = b.hi[a];
          }
          p.lo[3] = std::bit_cast<float>(uint32_t(i));
          p.hi[3] = ok ? 1.f : 0.f;
          if (ok) add(acc.root, p);
          acc.valid += ok;
        }
        return acc;
      },
      [](Boxes a, const Boxes& b) {
        a.valid += b.valid;
        a.root.geom.expand(b.root.geom);
        a.root.cent.expand(b.root.cent);
        return a;
      });
  if (boxes.valid != n) {
    refs.erase(std::remove_if(refs.begin(), refs.end(), [](const PrimRef& p) { return p.hi[3] == 0.f; }), refs.end());
  }
  Range root = boxes.root;
  root.end = uint32_t(refs.size());
  return root;
}

}  // namespace rayform::mesh_build
