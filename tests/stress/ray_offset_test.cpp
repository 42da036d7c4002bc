// Robust secondary rays (geometry/ray_offset.h through surface_point): random
// hits on spheres, planes, single triangles and a planar mesh under random
// instance transforms (translations 1e3 .. 1e6, scales 1e-4 .. 1e4, some
// anisotropy), through the whole pipeline (prepare_scene, intersect_scene,
// surface_point, the spawn functions, intersect_scene / occluded again).
//
// For each hit, with the exact surface taken as the float object-to-world
// matrix applied without rounding (its inverse computed in long double):
//  - side: the origins of a reflected and a transmitted ray (w on either side
//    of the geometric normal) lie strictly on the side w points to;
//  - self-intersection: the reflected ray hits nothing (every shape here is
//    convex or planar); the transmitted ray hits nothing either, except
//    inside a sphere, where its first hit must be the far side (t at least
//    half the exact chord);
//  - shadow ray: spawn_ray_to a point light on the lit side is not occluded;
//  - sphere chord: spawn_ray_to between the entry point and the far-side hit
//    of the transmitted ray (both ends offset) is not occluded.
// The fixed-epsilon policies run on the same hits: (A) origin moved 1e-4
// along the normal, (B) origin on the hit, tmin = 1e-4 (unit directions);
// shadow rays with origin (A) and tmax = 1 - 1e-4.
#include "rayform/geometry/ray_offset.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/scene/procedural_mesh.h"
#include "stress_common.h"

namespace rayform::stress {
namespace {

enum class Shape { sphere, plane, triangle, mesh };
const char* shape_name(Shape s) {
  switch (s) {
    case Shape::sphere: return "sphere";
    case Shape::plane: return "plane";
    case Shape::triangle: return "triangle";
    case Shape::mesh: return "planar_mesh";
  }
  return "?";
}

struct Counts {
  int64_t hits = 0, primary_misses = 0, spawned = 0, ambiguous_side = 0, shadow_rays = 0, chords = 0, unresolvable = 0;
  int64_t ours_side = 0, ours_self = 0, ours_shadow = 0, ours_chord = 0, ours_nonfinite = 0;
  int64_t a_side = 0, a_self = 0, a_shadow = 0, b_self = 0;
  Counts& operator+=(const Counts& o) {
    hits += o.hits;
    primary_misses += o.primary_misses;
    spawned += o.spawned;
    ambiguous_side += o.ambiguous_side;
    shadow_rays += o.shadow_rays;
    chords += o.chords;
    unresolvable += o.unresolvable;
    ours_side += o.ours_side;
    ours_self += o.ours_self;
    ours_shadow += o.ours_shadow;
    ours_chord += o.ours_chord;
    ours_nonfinite += o.ours_nonfinite;
    a_side += o.a_side;
    a_self += o.a_self;
    a_shadow += o.a_shadow;
    b_self += o.b_self;
    return *this;
  }
  int64_t ours() const { return ours_side + ours_self + ours_shadow + ours_chord + ours_nonfinite; }
  int64_t naive() const { return a_side + a_self + a_shadow + b_self; }
};

// The shape in object space, exactly (long double from the float data).
struct ExactShape {
  Shape kind;
  lvec3 centre;  // sphere
  ld radius = 0;
  lvec3 normal;   // plane, triangle, mesh (not normalised)
  ld offset = 0;  // plane: normal . x = offset
  lvec3 v0;       // triangle / mesh: a point of the plane
  // Signed distance, positive on the side the normal points to.
  ld side(lvec3 p) const {
    if (kind == Shape::sphere) return length(p - centre) - radius;
    if (kind == Shape::plane) return (dot(normal, p) - offset) / length(normal);
    return dot(p - v0, normal) / length(normal);
  }
  lvec3 outward(lvec3 s) const { return kind == Shape::sphere ? s - centre : normal; }
  // The nearest point of the surface (of its plane for triangles).
  lvec3 project(lvec3 p) const {
    if (kind == Shape::sphere) return centre + (radius / length(p - centre)) * (p - centre);
    const ld k = kind == Shape::plane ? (dot(normal, p) - offset) / dot(normal, normal)
                                      : dot(p - v0, normal) / dot(normal, normal);
    return p - k * normal;
  }
};

// Unit vector with the given cosine to unit n (long double not needed: test directions).
dvec3 around_normal(Rng& rng, dvec3 n, double cos_theta) {
  dvec3 a = std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
  dvec3 t1 = glm::normalize(glm::cross(n, a)), t2 = glm::cross(n, t1);
  double phi = rng.uniform(0.0, 6.283185307179586), s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return cos_theta * n + s * (std::cos(phi) * t1 + std::sin(phi) * t2);
}

float float_ulp(float x) { return next_float_up(std::abs(x)) - std::abs(x); }

Counts run(Shape kind, int64_t hits_wanted, uint64_t seed) {
  const int64_t per_transform = 50;
  return parallel_samples<Counts>(
      hits_wanted, per_transform, seed, [&](Rng& rng, Counts& c, int64_t begin, int64_t end) {
        // The object.
        Scene scene;
        ExactShape ex;
        ex.kind = kind;
        double object_size = 1.0;
        switch (kind) {
          case Shape::sphere: {
            Sphere s;
            s.center = vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            s.radius = float(rng.log_uniform(0.2, 2.0));
            scene.spheres.push_back(s);
            ex.centre = lvec3(s.center);
            ex.radius = s.radius;
            object_size = 2.0 * s.radius;
            break;
          }
          case Shape::plane: {
            Plane pl;
            pl.normal = vec3(rng.unit_vector() * rng.log_uniform(0.5, 2.0));
            pl.offset = float(rng.uniform(-1, 1));
            scene.planes.push_back(pl);
            ex.normal = lvec3(pl.normal);
            ex.offset = pl.offset;
            object_size = 4.0;
            break;
          }
          case Shape::triangle: {
            Triangle tri;
            do {
              for (vec3& v : tri.vertices) v = vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            } while (glm::length(glm::cross(tri.vertices[1] - tri.vertices[0], tri.vertices[2] - tri.vertices[0])) <
                     0.2f);
            scene.triangles.push_back(tri);
            ex.v0 = lvec3(tri.vertices[0]);
            ex.normal = cross(lvec3(tri.vertices[1]) - ex.v0, lvec3(tri.vertices[2]) - ex.v0);
            object_size = 2.0;
            break;
          }
          case Shape::mesh: {
            scene.meshes.push_back(make_grid(4, 4));  // [0,1]^2 in z = 0, normal +z
            ex.v0 = lvec3(0, 0, 0);
            ex.normal = lvec3(0, 0, 1);
            object_size = 1.0;
            break;
          }
        }
        // The instance transform: translate * rotate * scale; one in eight is the
        // identity (no transform: the shape is intersected in world space).
        const bool identity = rng.uniform() < 0.125;
        const double scale = identity ? 1.0 : rng.log_uniform(1e-4, 1e4);
        const dvec3 s3 =
            identity ? dvec3(1.0)
                     : scale * dvec3(rng.log_uniform(0.5, 2.0), rng.log_uniform(0.5, 2.0), rng.log_uniform(0.5, 2.0));
        const mat4 m =
            identity ? mat4(1.f) : make_affine(rng.rotation(), s3, rng.unit_vector() * rng.log_uniform(1e3, 1e6));
        Node root, leaf;
        root.kind = Node::Kind::transform;
        root.local = m;
        root.children = {1};
        leaf.kind = Node::Kind::shape;
        leaf.shape_kind = kind == Shape::sphere     ? ShapeKind::sphere
                          : kind == Shape::plane    ? ShapeKind::plane
                          : kind == Shape::triangle ? ShapeKind::triangle
                                                    : ShapeKind::mesh;
        leaf.shape = 0;
        scene.nodes = {root, leaf};
        scene.root = 0;
        const PreparedScene prepared = prepare_scene(scene);
        const LAffine to_world = to_laffine(prepared.instances.at(0).to_world);
        const LAffine to_object = inverse(to_world);
        const double world_size = object_size * std::max({s3.x, s3.y, s3.z});

        for (int64_t i = begin; i < end; ++i) {
          // A point of the exact surface, in object space.
          lvec3 s_obj;
          switch (kind) {
            case Shape::sphere: s_obj = ex.centre + ex.radius * lvec3(rng.unit_vector()); break;
            case Shape::plane: {
              lvec3 q(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
              s_obj = q - ((dot(ex.normal, q) - ex.offset) / dot(ex.normal, ex.normal)) * ex.normal;
              break;
            }
            case Shape::triangle: {
              double u = rng.uniform(), v = rng.uniform();
              if (u + v > 1) {
                u = 1 - u;
                v = 1 - v;
              }
              const Triangle& t = scene.triangles[0];
              s_obj = lvec3(t.vertices[0]) + ld(u) * (lvec3(t.vertices[1]) - lvec3(t.vertices[0])) +
                      ld(v) * (lvec3(t.vertices[2]) - lvec3(t.vertices[0]));
              break;
            }
            case Shape::mesh: s_obj = lvec3(rng.uniform(), rng.uniform(), 0.0); break;
          }
          // World point and normal (inverse transpose), and a camera on a visible side.
          const lvec3 s_w = to_world.point(s_obj);
          const lvec3 n_obj = ex.outward(s_obj);
          lvec3 n_w;
          for (int r = 0; r < 3; ++r)
            n_w[r] = to_object.m[0][r] * n_obj.x + to_object.m[1][r] * n_obj.y + to_object.m[2][r] * n_obj.z;
          const dvec3 n_wd = glm::normalize(dvec3(double(n_w.x), double(n_w.y), double(n_w.z)));
          const double view_side = kind == Shape::sphere || rng.uniform() < 0.5 ? 1.0 : -1.0;
          const dvec3 v = around_normal(rng, view_side * n_wd, rng.uniform(0.2, 1.0));
          const float ulp_s = float_ulp(float(std::max({std::abs(s_w.x), std::abs(s_w.y), std::abs(s_w.z)})));
          const double dist = std::max(world_size * rng.log_uniform(0.1, 10.0), 64.0 * ulp_s);
          const vec3 o = (s_w + ld(dist) * lvec3(v)).to_float();
          const vec3 d = (s_w - lvec3(o)).to_float();
          Ray ray;
          ray.origin = o;
          ray.direction = d;
          Hit hit;
          if (!intersect_scene(prepared, ray, &hit)) {
            ++c.primary_misses;
            continue;
          }
          ++c.hits;
          const SurfacePoint sp = surface_point(prepared, ray, hit);
          const vec3 ng = sp.geometric_normal;
          if (!is_finite(sp.position) || !is_finite(sp.position_error)) {
            ++c.ours_nonfinite;
            continue;
          }
          // The side the camera ray came from (the renderer's float decision).
          const float from_side = glm::dot(d, ng) < 0.f ? 1.f : -1.f;
          const vec3 p_naive = ray.at(hit.t);
          // The exact surface point at the hit, its outward normal, and that
          // normal in world space (inverse transpose). The hit may lie far from s:
          // the object-space ray is only as accurate as the float inverse
          // transform; on a sphere smaller than that error, even the world
          // position does not tell which side of the sphere was hit, so take the
          // point where the object-space ray met it.
          const lvec3 s_hit =
              ex.project(kind == Shape::sphere ? lvec3(to_object_space(prepared.instances[0], ray).at(hit.t))
                                               : to_object.point(lvec3(sp.position)));
          const lvec3 nh_obj = ex.outward(s_hit);
          lvec3 nh_w;
          for (int r = 0; r < 3; ++r)
            nh_w[r] = to_object.m[0][r] * nh_obj.x + to_object.m[1][r] * nh_obj.y + to_object.m[2][r] * nh_obj.z;

          // A sphere not much larger than the error of its hit points or the float
          // spacing there (e.g. 1e-4 at 1e6, where floats are 0.06 apart) has no
          // float point inside it near the hit for an origin to move to (and a
          // step of one float sideways leaves it, it is so curved): rays into
          // such spheres are not checked.
          const float reach =
              glm::dot(glm::abs(ng), sp.position_error) +
              2.f * float_ulp(std::max({std::abs(sp.position.x), std::abs(sp.position.y), std::abs(sp.position.z)}));
          const bool sphere_resolvable =
              kind == Shape::sphere && 8.f * reach < float(ex.radius) * float(std::min({s3.x, s3.y, s3.z}));
          for (int transmit = 0; transmit < 2; ++transmit) {
            const float side = transmit ? -from_side : from_side;
            const vec3 w = vec3(around_normal(rng, dvec3(side * ng), rng.uniform(0.0, 1.0)));
            if (glm::dot(w, ng) == 0.f) continue;
            // The exact side w points to, from the exact normal; the float decision
            // of offset_ray_origin (sign of dot(w, ng)) must agree for the check to mean anything.
            const lvec3 w_obj = to_object.vector(lvec3(w));
            const ld exact_side = dot(w_obj, nh_obj);  // = dot(w, nh_w): the inverse transpose keeps sides
            const bool float_positive = glm::dot(w, ng) >= 0.f;
            const ld ng_dot = dot(lvec3(ng), nh_w);  // ng may be the flipped normal
            const bool exact_positive = (exact_side > 0) == (ng_dot > 0);
            const bool side_checkable = float_positive == exact_positive && exact_side != 0;
            const ld want = exact_side > 0 ? 1 : -1;  // sign of ex.side() the origin must have
            if (kind == Shape::sphere && want < 0 && !sphere_resolvable) {
              ++c.unresolvable;
              continue;
            }
            ++c.spawned;
            if (!side_checkable) ++c.ambiguous_side;

            auto is_self_hit = [&](const Ray& r) {
              Hit h2;
              if (!intersect_scene(prepared, r, &h2)) return kind == Shape::sphere && want < 0;  // lost inside a sphere
              if (!(kind == Shape::sphere && want < 0)) return true;
              // Inside a sphere: the first hit must be the far side.
              const lvec3 f = to_object.point(lvec3(r.origin)) - ex.centre, wo = to_object.vector(lvec3(r.direction));
              const ld a = dot(wo, wo), b = dot(f, wo), cc = dot(f, f) - ex.radius * ex.radius;
              const ld disc = std::max<ld>(0, b * b - a * cc);
              const ld t_far = b > 0 ? -cc / (b + std::sqrt(disc)) : (-b + std::sqrt(disc)) / a;
              return ld(h2.t) < 0.5L * t_far;
            };

            // Ours.
            const Ray r = spawn_ray(sp.position, sp.position_error, ng, w);
            if (!is_finite(r.origin)) {
              ++c.ours_nonfinite;
              continue;
            }
            if (side_checkable && !(ex.side(to_object.point(lvec3(r.origin))) * want > 0)) {
              ++c.ours_side;
              if (std::getenv("RAYFORM_STRESS_DEBUG"))
                std::cout << "wrong side " << shape_name(kind) << " identity=" << identity << " scale=" << scale
                          << " want=" << double(want)
                          << " side(o)=" << double(ex.side(to_object.point(lvec3(r.origin))))
                          << " side(p)=" << double(ex.side(to_object.point(lvec3(sp.position))))
                          << " |p|=" << glm::length(sp.position) << " err=" << glm::length(sp.position_error)
                          << " offset=" << glm::length(r.origin - sp.position)
                          << " cos=" << glm::dot(glm::normalize(w), ng) << " ng.nh=" << double(ng_dot / length(nh_w))
                          << " radius=" << double(ex.radius) << "\n";
            }
            const bool self = is_self_hit(r);
            c.ours_self += self;
            if (self && std::getenv("RAYFORM_STRESS_DEBUG")) {
              Hit h2;
              bool any = intersect_scene(prepared, r, &h2);
              std::cout << "self-hit " << shape_name(kind) << " identity=" << identity << " scale=" << scale
                        << " transmit=" << transmit << " want=" << double(want)
                        << " side(o)=" << double(ex.side(to_object.point(lvec3(r.origin))))
                        << " |p|=" << glm::length(sp.position) << " err=" << glm::length(sp.position_error)
                        << " cos=" << glm::dot(glm::normalize(w), ng) << " radius=" << double(ex.radius)
                        << " hit=" << any << " t=" << (any ? h2.t : 0.f) << "\n";
            }

            // Fixed epsilon (A): origin 1e-4 along the normal, to w's side.
            Ray ra;
            ra.origin = p_naive + 1e-4f * (float_positive ? ng : -ng);
            ra.direction = glm::normalize(w);
            if (side_checkable && !(ex.side(to_object.point(lvec3(ra.origin))) * want > 0)) ++c.a_side;
            c.a_self += is_self_hit(ra);
            // Fixed epsilon (B): origin on the hit, hits closer than 1e-4 ignored.
            Ray rb;
            rb.origin = p_naive;
            rb.direction = glm::normalize(w);
            rb.tmin = 1e-4f;
            c.b_self += is_self_hit(rb);

            // Sphere chord: from the entry point to the far-side hit, both ends offset.
            if (kind == Shape::sphere && transmit && want < 0) {
              Hit h2;
              if (intersect_scene(prepared, r, &h2)) {
                const SurfacePoint sp2 = surface_point(prepared, r, h2);
                const Ray chord = spawn_ray_to(sp.position, sp.position_error, ng, sp2.position, sp2.position_error,
                                               sp2.geometric_normal);
                ++c.chords;
                c.ours_chord += occluded(prepared, chord);
              }
            }
          }

          // A point light on a lit side (outside a sphere, either side of a plane), and its shadow ray.
          {
            const double light_side = kind == Shape::sphere || rng.uniform() < 0.5 ? 1.0 : -1.0;
            const dvec3 nh = glm::normalize(dvec3(double(nh_w.x), double(nh_w.y), double(nh_w.z)));
            const dvec3 lv = around_normal(rng, light_side * nh, rng.uniform(0.05, 1.0));
            const double ldist = std::max(world_size * rng.log_uniform(0.1, 100.0), 64.0 * ulp_s);
            const vec3 light = (lvec3(sp.position) + ld(ldist) * lvec3(lv)).to_float();
            // Only lights strictly on that side of the surface and of its tangent plane at the hit.
            const lvec3 light_obj = to_object.point(lvec3(light));
            if (ex.side(light_obj) * ld(light_side) > 0 && dot(light_obj - s_hit, nh_obj) * ld(light_side) > 0) {
              ++c.shadow_rays;
              c.ours_shadow += occluded(prepared, spawn_ray_to(sp.position, sp.position_error, ng, light));
              Ray ra;
              ra.origin = p_naive + 1e-4f * (glm::dot(light - p_naive, ng) >= 0.f ? ng : -ng);
              ra.direction = light - ra.origin;
              ra.tmax = 1.f - 1e-4f;
              c.a_shadow += occluded(prepared, ra);
            }
          }
        }
      });
}

void check(Shape kind, uint64_t seed) {
  const Counts c = run(kind, scaled(60000), seed);
  const std::string name = std::string("ray_offset.") + shape_name(kind);
  std::cout << "[stress] " << name << ": " << c.hits << " hits (" << c.primary_misses << " camera rays missed), "
            << c.spawned << " spawned rays (" << c.ambiguous_side << " tangent, side not checked), " << c.shadow_rays
            << " shadow rays, " << c.chords << " chords";
  if (kind == Shape::sphere)
    std::cout << " (" << c.unresolvable << " rays into spheres smaller than their error bound skipped)";
  std::cout << ".\n"
            << "    ours: wrong side " << c.ours_side << ", self-intersections " << c.ours_self << ", false shadows "
            << c.ours_shadow << ", blocked chords " << c.ours_chord << ", non-finite " << c.ours_nonfinite << "\n"
            << "    fixed eps (A) origin + 1e-4 n: wrong side " << c.a_side << ", self-intersections " << c.a_self
            << ", false shadows " << c.a_shadow << "; (B) tmin = 1e-4: self-intersections " << c.b_self << "\n";
  report(name, c.spawned + c.shadow_rays + c.chords, c.ours(), c.naive(), "fixed_eps_1e-4");
  EXPECT_GT(c.hits, c.primary_misses);
  EXPECT_EQ(c.ours_nonfinite, 0);
  EXPECT_EQ(c.ours_side, 0);
  EXPECT_EQ(c.ours_self, 0);
  EXPECT_EQ(c.ours_shadow, 0);
  EXPECT_EQ(c.ours_chord, 0);
  EXPECT_GT(c.naive(), 0) << "the fixed-epsilon policies were expected to fail somewhere at these scales";
}

TEST(StressRayOffset, Sphere) { check(Shape::sphere, 41); }
TEST(StressRayOffset, Plane) { check(Shape::plane, 42); }
TEST(StressRayOffset, Triangle) { check(Shape::triangle, 43); }
TEST(StressRayOffset, PlanarMesh) { check(Shape::mesh, 44); }

}  // namespace
}  // namespace rayform::stress
