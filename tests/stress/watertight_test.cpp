// Watertightness: rays aimed exactly at the edges and vertices of closed
// meshes (the aim point is a barycentric point with one or two zero
// coordinates, computed in float from the transformed vertices) must never
// slip through the mesh. Every mesh gets random rotations, non-uniform scales
// (1e-3 .. 1e3) and translations (up to 1e3 times its size), applied to the
// vertices in float; ray origins lie outside the mesh.
//
// A ray counts only when every triangle around the aimed edge / vertex faces
// it (checked in double), so that its line must cross the surface there: it
// has to hit at t ~ 1 (the aim point) and, the mesh being closed, leave again
// later. A failure is a ray with no hit at the aim point or fewer than two
// crossings. Checked with the BVH (intersect_mesh, all crossings enumerated
// by moving tmin) and with a plain loop of intersect_triangle over every
// triangle; the same rays go through a Möller-Trumbore loop with the usual
// fixed epsilons (|det| < 1e-6 culled, t > 1e-4) for comparison.
#include "rayform/accel/mesh_accel.h"
#include "rayform/geometry/triangle_intersect.h"
#include "rayform/scene/procedural_mesh.h"
#include "stress_common.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

namespace rayform::stress {
namespace {

// Möller-Trumbore as commonly written, with its fixed epsilons (test only).
bool naive_moller_trumbore(vec3 o, vec3 d, vec3 p0, vec3 p1, vec3 p2, float* t_hit) {
  const float eps = 1e-6f;
  vec3 e1 = p1 - p0, e2 = p2 - p0;
  vec3 pv = glm::cross(d, e2);
  float det = glm::dot(e1, pv);
  if (std::abs(det) < eps) return false;
  float inv = 1.f / det;
  vec3 tv = o - p0;
  float u = glm::dot(tv, pv) * inv;
  if (u < 0.f || u > 1.f) return false;
  vec3 qv = glm::cross(tv, e1);
  float v = glm::dot(d, qv) * inv;
  if (v < 0.f || u + v > 1.f) return false;
  float t = glm::dot(e2, qv) * inv;
  if (!(t > 1e-4f)) return false;
  *t_hit = t;
  return true;
}

// One hit along the ray: distance, triangle, and whether the triangle faces
// away from the ray (an exit from the closed mesh).
struct RayHit {
  float t;
  uint32_t triangle;
  bool exit;
};

// The ray slips through when no triangle around the aim point is hit (a crack
// at the aimed edge or vertex) or when nothing is hit beyond that entry on the
// way out (the ray entered but never left the closed mesh).
bool passes_through(const std::vector<RayHit>& hits, const std::vector<uint8_t>& around) {
  float t_entry = infinity;
  for (const RayHit& h : hits)
    if (around[h.triangle]) t_entry = std::min(t_entry, h.t);
  if (t_entry == infinity) return true;
  for (const RayHit& h : hits)
    if (h.exit && h.t > t_entry) return false;
  return true;
}

// With RAYFORM_STRESS_DEBUG set, prints a failing ray exactly (hex floats)
// with the triangles around its aim point and the hits found.
void debug_dump(const char* what, vec3 origin, vec3 dir, const std::vector<vec3>& pos, const Mesh& mesh,
                const std::vector<uint32_t>& around, const std::vector<RayHit>& hits) {
  if (!std::getenv("RAYFORM_STRESS_DEBUG")) return;
  auto hex = [](vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%a %a %a", v.x, v.y, v.z);
    return std::string(buf);
  };
  std::ostringstream s;
  s << "through the mesh (" << what << "): origin " << hex(origin) << " direction " << hex(dir) << "\n";
  for (uint32_t g : around)
    s << "  around " << g << ": " << hex(pos[mesh.indices[3 * g]]) << " | " << hex(pos[mesh.indices[3 * g + 1]])
      << " | " << hex(pos[mesh.indices[3 * g + 2]]) << "\n";
  for (const RayHit& h : hits)
    s << "  hit t=" << h.t << " triangle " << h.triangle << (h.exit ? " (exit)" : "") << "\n";
  std::cout << s.str();
}

struct Topology {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edge_faces;
  std::vector<std::vector<uint32_t>> vertex_faces;
};

Topology topology(const Mesh& m) {
  Topology t;
  t.vertex_faces.resize(m.positions.size());
  for (uint32_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = m.indices[3 * f + k], b = m.indices[3 * f + (k + 1) % 3];
      t.edge_faces[std::minmax(a, b)].push_back(f);
      t.vertex_faces[a].push_back(f);
    }
  return t;
}

struct Counts {
  int64_t rays = 0, loop_rays = 0, naive_rays = 0, skipped = 0;
  int64_t ours_bvh = 0, ours_loop = 0, naive = 0, range_violations = 0;
  Counts& operator+=(const Counts& o) {
    rays += o.rays;
    loop_rays += o.loop_rays;
    naive_rays += o.naive_rays;
    skipped += o.skipped;
    ours_bvh += o.ours_bvh;
    ours_loop += o.ours_loop;
    naive += o.naive;
    range_violations += o.range_violations;
    return *this;
  }
};

// Smallest |cos| between a ray and the triangles around its aim point
// (RAYFORM_STRESS_MIN_COS overrides it, to explore nearer tangency).
double min_cos() {
  const char* e = std::getenv("RAYFORM_STRESS_MIN_COS");
  return e && *e ? std::atof(e) : 1e-2;
}

Counts run_mesh(const Mesh& mesh, int64_t rays, uint64_t seed) {
  const double min_cos = stress::min_cos();
  const Topology topo = topology(mesh);
  for (const auto& [edge, faces] : topo.edge_faces) EXPECT_EQ(faces.size(), 2u) << "the mesh must be closed";
  const int64_t per_transform = 2000;
  return parallel_samples<Counts>(rays, per_transform, seed, [&](Rng& rng, Counts& c, int64_t begin, int64_t end) {
    // A random transform, applied to the vertices in float.
    const double size = rng.log_uniform(1e-3, 1e3);
    const dvec3 s = size * dvec3(rng.log_uniform(0.3, 3.0), rng.log_uniform(0.3, 3.0), rng.log_uniform(0.3, 3.0));
    const glm::dmat3 rot = rng.rotation();
    const dvec3 tr = rng.unit_vector() * size * rng.log_uniform(1e-2, 1e3);
    std::vector<vec3> pos(mesh.positions.size());
    dvec3 centre(0.0);
    for (size_t i = 0; i < pos.size(); ++i) {
      pos[i] = vec3(rot * (s * dvec3(mesh.positions[i])) + tr);
      centre += dvec3(pos[i]);
    }
    centre /= double(pos.size());
    double radius = 0.0;
    for (const vec3& p : pos) radius = std::max(radius, glm::length(dvec3(p) - centre));
    const MeshAccel accel = build_mesh_accel(pos, mesh.indices);
    const uint32_t tris = uint32_t(mesh.triangle_count());
    auto face_normal = [&](uint32_t f) {
      dvec3 a(pos[mesh.indices[3 * f]]), b(pos[mesh.indices[3 * f + 1]]), cc(pos[mesh.indices[3 * f + 2]]);
      return glm::cross(b - a, cc - a);
    };
    std::vector<RayHit> hits;
    std::vector<uint8_t> around(tris, 0);
    std::vector<uint32_t> marked;
    for (int64_t i = begin; i < end;) {
      const uint32_t f = rng.index(tris);
      const int k = int(rng.index(3));
      const bool vertex = rng.uniform() < 1.0 / 3.0;
      const uint32_t ia = mesh.indices[3 * f + k], ib = mesh.indices[3 * f + (k + 1) % 3];
      // Aim point: barycentrics (1 - b, b, 0) on an edge, or (1, 0, 0) at a vertex, in float.
      const float b = vertex ? 0.f : float(rng.uniform(0.0, 1.0));
      const vec3 target = vertex ? pos[ia] : (1.f - b) * pos[ia] + b * pos[ib];
      const vec3 origin = vec3(centre + rng.unit_vector() * radius * rng.log_uniform(1.2, 30.0));
      const vec3 dir = target - origin;
      // Triangles that count as a hit at the aim point: those around its edge's
      // end vertices (the float aim point may sit an ulp off the edge).
      for (uint32_t g : marked) around[g] = 0;
      marked = topo.vertex_faces[ia];
      if (!vertex) marked.insert(marked.end(), topo.vertex_faces[ib].begin(), topo.vertex_faces[ib].end());
      // Only rays whose line must cross the surface there: every one of those
      // triangles faces the ray, not nearly edge-on (|cos| >= 1e-2, checked in
      // double), so that the rounding of the vertices and of the aim point
      // (far below 1e-2 of a triangle's size) cannot move the line off the
      // surface; nearer to tangency, hit or miss is legitimately ambiguous.
      bool crossing = true;
      for (uint32_t g : marked) {
        const dvec3 n = face_normal(g);
        crossing &= glm::dot(dvec3(dir), n) < -min_cos * glm::length(dvec3(dir)) * glm::length(n);
      }
      if (!crossing) {
        ++c.skipped;
        continue;
      }
      ++i;
      ++c.rays;
      for (uint32_t g : marked) around[g] = 1;
      auto exits = [&](uint32_t g) { return glm::dot(dvec3(dir), face_normal(g)) > 0.0; };
      Ray ray;
      ray.origin = origin;
      ray.direction = dir;

      // Ours, with the BVH: every crossing in turn, moving tmin past the last hit.
      hits.clear();
      for (int step = 0; step < 32; ++step) {
        float tmax = infinity;
        MeshHit mh;
        if (!intersect_mesh(accel, ray, tmax, &mh)) break;
        hits.push_back({tmax, mh.triangle, exits(mh.triangle)});
        if (tmax > ray.tmin) {
          ray.tmin = tmax;
        } else {  // outside the open interval (tmin, tmax): a bug of its own; step on
          ++c.range_violations;
          ray.tmin = next_float_up(ray.tmin);
        }
      }
      ray.tmin = 0.f;
      const bool bvh_fail = passes_through(hits, around);
      c.ours_bvh += bvh_fail;
      if (bvh_fail) debug_dump("BVH", origin, dir, pos, mesh, marked, hits);

      // The plain loops cost a test per triangle: every 2nd ray for ours, every 4th for the naive one.
      if (i % 2 != 0) continue;
      ++c.loop_rays;

      // Ours, plain loop over every triangle.
      hits.clear();
      const TriangleRay tr_ray = make_triangle_ray(ray);
      for (uint32_t g = 0; g < tris; ++g) {
        TriangleHit th;
        if (intersect_triangle(tr_ray, pos[mesh.indices[3 * g]], pos[mesh.indices[3 * g + 1]],
                               pos[mesh.indices[3 * g + 2]], 0.f, infinity, &th))
          hits.push_back({th.t, g, exits(g)});
      }
      const bool loop_fail = passes_through(hits, around);
      c.ours_loop += loop_fail;
      if (loop_fail) debug_dump("plain loop", origin, dir, pos, mesh, marked, hits);

      // Fixed-epsilon Möller-Trumbore, same loop.
      if (i % 4 != 0) continue;
      ++c.naive_rays;
      hits.clear();
      for (uint32_t g = 0; g < tris; ++g) {
        float t;
        if (naive_moller_trumbore(origin, dir, pos[mesh.indices[3 * g]], pos[mesh.indices[3 * g + 1]],
                                  pos[mesh.indices[3 * g + 2]], &t))
          hits.push_back({t, g, exits(g)});
      }
      c.naive += passes_through(hits, around);
    }
  });
}

void check(const char* name, const Mesh& mesh, int64_t rays, uint64_t seed) {
  Counts c = run_mesh(mesh, rays, seed);
  std::cout << "[stress] watertight " << name << " (" << mesh.triangle_count() << " triangles; " << c.skipped
            << " candidate rays near tangency skipped): through the mesh: ours BVH " << c.ours_bvh << " of " << c.rays
            << ", ours plain loop " << c.ours_loop << " of " << c.loop_rays << ", Moller-Trumbore eps=1e-6 " << c.naive
            << " of " << c.naive_rays << "; BVH hits with t <= tmin: " << c.range_violations << "\n";
  report(std::string("watertight.") + name, c.rays, c.ours_bvh + c.ours_loop, c.naive, "moller_trumbore_eps");
  EXPECT_EQ(c.ours_bvh, 0);
  EXPECT_EQ(c.range_violations, 0) << "intersect_mesh returned t <= ray.tmin (the interval is open)";
  EXPECT_EQ(c.ours_loop, 0);
  EXPECT_GT(c.naive, 0) << "the fixed-epsilon intersector was expected to leak";
}

// 10^6 rays in all at scale 1: 400k + 200k + 400k.
TEST(StressWatertight, Icosphere) { check("icosphere3", make_icosphere(3), scaled(400000), 11); }
TEST(StressWatertight, Cube) { check("cube", make_cube(), scaled(200000), 12); }
TEST(StressWatertight, BumpyTorus) { check("bumpy_torus", make_bumpy_torus(2000, 7), scaled(400000), 13); }

}  // namespace
}  // namespace rayform::stress
