// Degenerate input: zero-area triangles, zero-scale and singular transforms,
// zero-length and non-finite normals, NaN / Inf vertices, zero radii. No
// crash, no NaN out of the intersection, surface and offset functions, and
// prepare_scene + render() give finite pixels (also with shadows and
// reflections, which spawn secondary rays from these surfaces).
// The fixed-epsilon habit (origin + 1e-4 * normalize(n)) runs on the same
// hits and inputs, counting the NaN it makes.
#include "rayform/geometry/plane_intersect.h"
#include "rayform/geometry/ray_offset.h"
#include "rayform/geometry/sphere_intersect.h"
#include "rayform/geometry/triangle_intersect.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/scene/procedural_mesh.h"
#include "stress_common.h"

#include <limits>

namespace rayform::stress {
namespace {

constexpr float nan_f = std::numeric_limits<float>::quiet_NaN();
constexpr float inf_f = std::numeric_limits<float>::infinity();

bool has_nan(vec3 v) { return std::isnan(v.x) || std::isnan(v.y) || std::isnan(v.z); }
vec3 naive_offset(vec3 p, vec3 n, vec3 w) {
  vec3 nn = glm::normalize(n);
  return p + 1e-4f * (glm::dot(nn, w) < 0.f ? -nn : nn);
}

// Awkward values for vectors and scalars.
const float odd_scalars[] = {0.f, -0.f, 1e-38f, 1e-45f, 1.f, -1.f, 3e38f, -3e38f, inf_f, -inf_f, nan_f};
vec3 odd_vector(Rng& rng) {
  auto s = [&] { return rng.uniform() < 0.5 ? float(rng.uniform(-2, 2)) : odd_scalars[rng.index(11)]; };
  return vec3(s(), s(), s());
}

TEST(StressDegenerate, KernelsNeverMakeNaN) {
  Rng rng(51);
  int64_t calls = 0, nan_out = 0, naive_nan = 0;
  const int64_t n = scaled(200000);
  for (int64_t i = 0; i < n; ++i) {
    // Finite ray, degenerate primitives.
    Ray ray;
    ray.origin = vec3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3));
    ray.direction = vec3(rng.unit_vector());
    vec3 a = odd_vector(rng), b = rng.uniform() < 0.3 ? a : odd_vector(rng),
         c = rng.uniform() < 0.3 ? b : odd_vector(rng);
    if (rng.uniform() < 0.3) c = a + 0.5f * (b - a);  // collinear: zero area
    TriangleHit th;
    ++calls;
    if (intersect_triangle(ray, a, b, c, &th)) {
      nan_out += std::isnan(th.t) || std::isnan(th.b0) || std::isnan(th.b1) || std::isnan(th.b2) || !(th.t > 0.f);
      const PointError pe = triangle_point(a, b, c, th.b0, th.b1, th.b2);
      nan_out += has_nan(pe.p) || has_nan(pe.error);
      const vec3 ng = glm::cross(b - a, c - a);
      nan_out += has_nan(offset_ray_origin(pe.p, pe.error, ng, -ray.direction));
      naive_nan += has_nan(naive_offset(ray.at(th.t), ng, -ray.direction));
    }
    float t;
    const vec3 centre = odd_vector(rng);
    const float radius = odd_scalars[rng.index(11)];
    ++calls;
    if (intersect_sphere(ray, centre, radius, &t)) {
      nan_out += std::isnan(t);
      const PointError pe = sphere_point(ray.at(t), centre, radius);
      nan_out += has_nan(pe.p) && !has_nan(ray.at(t));
    }
    const vec3 pn = odd_vector(rng);
    const float poff = odd_scalars[rng.index(11)];
    ++calls;
    if (intersect_plane(ray, pn, poff, &t)) {
      nan_out += std::isnan(t);
      const PointError pe = plane_point(ray.at(t), pn, poff);
      nan_out += has_nan(pe.p) || has_nan(pe.error);
      nan_out += has_nan(offset_ray_origin(pe.p, pe.error, pn, ray.direction));
      naive_nan += has_nan(naive_offset(ray.at(t), pn, ray.direction));
    }
    // Offsets with awkward normals, errors and directions at a finite point.
    const vec3 p(rng.uniform(-1e6, 1e6), rng.uniform(-1, 1), rng.uniform(-1e-6, 1e-6));
    const vec3 e = rng.uniform() < 0.5 ? vec3(0.f) : glm::abs(odd_vector(rng));
    const vec3 nrm = rng.uniform() < 0.3 ? vec3(0.f) : odd_vector(rng), w = odd_vector(rng);
    ++calls;
    const vec3 o = offset_ray_origin(p, e, nrm, w);
    const bool finite_in = is_finite(e) && !has_nan(w);
    nan_out += finite_in && has_nan(o);
    if (finite_in) naive_nan += has_nan(naive_offset(p, nrm, w));
    // Points through singular and zero-scale matrices.
    mat4 m(1.f);
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) m[col][row] = rng.uniform() < 0.4 ? 0.f : float(rng.uniform(-2, 2));
    if (rng.uniform() < 0.3) m[0] = m[1] * 2.f;  // rank deficient
    ++calls;
    const PointError tp = transform_point(m, PointError{p, gamma_bound(3) * glm::abs(p)});
    nan_out += has_nan(tp.p) || has_nan(tp.error);
  }
  std::cout << "[stress] degenerate kernels: " << calls << " calls with degenerate input; ours " << nan_out
            << " NaN outputs; origin + 1e-4 * normalize(n): " << naive_nan << " NaN origins\n";
  report("degenerate.kernels", calls, nan_out, naive_nan, "normalize_plus_1e-4");
  EXPECT_EQ(nan_out, 0);
  EXPECT_GT(naive_nan, 0);
}

// A scene full of degenerate shapes around some ordinary ones.
Scene degenerate_scene() {
  Scene s;
  Camera cam;
  cam.center = vec3(0, 0, 8);
  cam.direction = vec3(0, 0, -1);
  cam.fov_deg = 60.f;
  s.cameras.push_back(cam);
  Light sun;
  sun.direction = vec3(-1, -2, -1);
  Light bulb;
  bulb.kind = Light::Kind::point;
  bulb.position = vec3(2, 3, 4);
  bulb.falloff = 0.1f;
  s.lights = {sun, bulb};
  Material mirror;
  mirror.diffuse = vec3(0.5f);
  mirror.specular = vec3(0.5f);
  mirror.shininess = 20.f;
  Material glass = mirror;
  glass.refraction_index = 1.5f;
  s.materials = {Material{}, mirror, glass};

  // Spheres: ordinary, zero radius, negative radius, NaN centre, infinite radius.
  s.spheres = {{vec3(0, 0, 0), 1.f},
               {vec3(1, 1, 0), 0.f},
               {vec3(-1.5f, 0, 0), -0.5f},
               {vec3(nan_f, 0, 0), 1.f},
               {vec3(0, -1, 0), inf_f}};
  // Planes: ordinary, zero normal, NaN offset, infinite normal.
  s.planes = {{vec3(0, 1, 0), -2.f}, {vec3(0.f), 1.f}, {vec3(1, 0, 0), nan_f}, {vec3(0, 0, inf_f), 0.f}};
  // Triangles: ordinary, zero area (collinear, a point), NaN and Inf vertices, huge.
  s.triangles = {{{vec3(-2, -1, 1), vec3(2, -1, 1), vec3(0, 2, 1)}},
                 {{vec3(-1, 0, 2), vec3(0, 0, 2), vec3(1, 0, 2)}},
                 {{vec3(0.5f), vec3(0.5f), vec3(0.5f)}},
                 {{vec3(nan_f, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)}},
                 {{vec3(-inf_f, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)}},
                 {{vec3(-3e38f, -3e38f, 0), vec3(3e38f, -3e38f, 0), vec3(0, 3e38f, 0)}}};
  // Meshes: an icosphere with some NaN / Inf vertices and zero-length vertex
  // normals; a cube squashed flat (zero-area faces); an ordinary torus.
  Mesh ico = make_icosphere(2);
  ico.positions[3] = vec3(nan_f);
  ico.positions[7] = vec3(inf_f, 0, 0);
  for (size_t i = 0; i < ico.normals.size(); i += 2) ico.normals[i] = vec3(0.f);
  ico.normals[5] = vec3(nan_f);
  Mesh flat = make_cube();
  for (vec3& p : flat.positions) p.z = 0.f;
  flat.normals.assign(flat.positions.size(), vec3(0.f));
  s.meshes = {ico, flat, make_bumpy_torus(500)};

  // Nodes: root group; each shape once untransformed, then under degenerate transforms.
  auto shape = [&](ShapeKind k, int i, int material) {
    Node n;
    n.kind = Node::Kind::shape;
    n.shape_kind = k;
    n.shape = i;
    n.material = material;
    s.nodes.push_back(n);
    return int(s.nodes.size()) - 1;
  };
  auto transform = [&](mat4 m, int child) {
    Node n;
    n.kind = Node::Kind::transform;
    n.local = m;
    n.children = {child};
    s.nodes.push_back(n);
    return int(s.nodes.size()) - 1;
  };
  Node root;
  root.kind = Node::Kind::group;
  s.nodes.push_back(root);
  std::vector<int> children;
  int material = 0;
  auto all_shapes = [&](auto&& wrap) {
    for (int i = 0; i < int(s.spheres.size()); ++i)
      children.push_back(wrap(shape(ShapeKind::sphere, i, material++ % 3)));
    for (int i = 0; i < int(s.planes.size()); ++i) children.push_back(wrap(shape(ShapeKind::plane, i, material++ % 3)));
    for (int i = 0; i < int(s.triangles.size()); ++i)
      children.push_back(wrap(shape(ShapeKind::triangle, i, material++ % 3)));
    for (int i = 0; i < int(s.meshes.size()); ++i) children.push_back(wrap(shape(ShapeKind::mesh, i, material++ % 3)));
  };
  all_shapes([](int n) { return n; });
  mat4 zero_scale(1.f);
  zero_scale[0][0] = zero_scale[1][1] = zero_scale[2][2] = 0.f;
  mat4 flat_scale(1.f);
  flat_scale[1][1] = 0.f;  // singular: squashes y
  mat4 rank_one(0.f);
  rank_one[0] = vec4(1, 1, 1, 0);
  rank_one[3] = vec4(0.5f, 0, 0, 1);
  mat4 tiny(1e-30f);
  tiny[3] = vec4(0, 0, 0, 1);
  mat4 nan_matrix(1.f);
  nan_matrix[2][1] = nan_f;
  for (const mat4& m : {zero_scale, flat_scale, rank_one, tiny, nan_matrix})
    all_shapes([&](int n) { return transform(m, n); });
  s.nodes[0].children = children;
  s.root = 0;
  return s;
}

TEST(StressDegenerate, SceneQueriesAndRender) {
  const Scene scene = degenerate_scene();
  PreparedScene prepared;
  ASSERT_NO_THROW(prepared = prepare_scene(scene));

  // Random rays through the scene: hits, surface points, spawned rays.
  Rng rng(52);
  int64_t rays = 0, hits = 0, ours_bad = 0, naive_nan = 0;
  const int64_t n = scaled(200000);
  for (int64_t i = 0; i < n; ++i) {
    Ray ray;
    ray.origin = vec3(rng.unit_vector() * rng.uniform(0.0, 10.0));
    ray.direction = vec3(rng.unit_vector());
    ++rays;
    Hit hit;
    if (!intersect_scene(prepared, ray, &hit)) continue;
    ++hits;
    const SurfacePoint sp = surface_point(prepared, ray, hit);
    bool bad = !std::isfinite(hit.t) || std::isnan(hit.b1) || std::isnan(hit.b2);
    bad |= !is_finite(sp.position) || has_nan(sp.position_error) || !is_finite(sp.normal) ||
           !is_finite(sp.geometric_normal);
    const Ray r = spawn_ray(sp.position, sp.position_error, sp.geometric_normal, -ray.direction);
    const Ray s = spawn_ray_to(sp.position, sp.position_error, sp.geometric_normal, vec3(2, 3, 4));
    bad |= has_nan(r.origin) || has_nan(s.origin) || has_nan(s.direction);
    Hit h2;
    if (intersect_scene(prepared, r, &h2)) bad |= !std::isfinite(h2.t);
    (void)occluded(prepared, s);
    ours_bad += bad;
    if (bad && std::getenv("RAYFORM_STRESS_DEBUG")) {
      const Instance& in = prepared.instances[hit.instance];
      std::cout << "bad hit: instance " << hit.instance << " kind " << int(in.kind) << " shape " << in.shape
                << " transform " << in.has_transform << " t " << hit.t << " b " << hit.b1 << "," << hit.b2 << " pos "
                << sp.position.x << "," << sp.position.y << "," << sp.position.z << " err " << sp.position_error.x
                << " n " << sp.normal.x << " ng " << sp.geometric_normal.x << " r.o " << r.origin.x << "\n";
    }
    // The fixed-epsilon habit with the raw object normal of the hit (zero for zero-area faces).
    const Instance& inst = prepared.instances[hit.instance];
    vec3 raw(0.f, 0.f, 1.f);
    if (inst.kind == ShapeKind::triangle) {
      const auto& v = scene.triangles[inst.shape].vertices;
      raw = inst.normal_to_world * glm::cross(v[1] - v[0], v[2] - v[0]);
    } else if (inst.kind == ShapeKind::mesh && !scene.meshes[inst.shape].normals.empty()) {
      const Mesh& m = scene.meshes[inst.shape];
      raw = inst.normal_to_world * m.normals[m.indices[3 * hit.primitive]];
    } else if (inst.kind == ShapeKind::sphere) {
      const Sphere& sph = scene.spheres[inst.shape];
      raw = inst.normal_to_world * ((to_object_space(inst, ray).at(hit.t) - sph.center) / sph.radius);
    } else if (inst.kind == ShapeKind::plane) {
      raw = inst.normal_to_world * scene.planes[inst.shape].normal;
    }
    naive_nan += has_nan(naive_offset(ray.at(hit.t), raw, -ray.direction));
  }

  // Tiny renders: plain, and with shadows and reflections / refraction.
  int64_t pixels = 0, bad_pixels = 0;
  for (int variant = 0; variant < 2; ++variant) {
    RenderOptions o;
    o.width = 24;
    o.height = 16;
    o.threads = 1;
    o.depth = o.normals = true;
    o.shadows = variant == 1;
    o.bounces = variant == 1 ? 3 : 0;
    RenderResult res;
    ASSERT_NO_THROW(res = render(prepared, o));
    for (float v : res.color.pixels) {
      ++pixels;
      bad_pixels += !std::isfinite(v);
    }
    for (const vec3& nrm : res.normals) bad_pixels += !is_finite(nrm);
    for (float d : res.depth) bad_pixels += std::isnan(d);
  }
  std::cout << "[stress] degenerate scene: " << prepared.instances.size() << " instances, " << rays << " rays, " << hits
            << " hits; ours " << ours_bad << " hits with NaN/non-finite output, " << bad_pixels << " of " << pixels
            << " pixel values not finite; origin + 1e-4 * normalize(n): " << naive_nan << " NaN origins\n";
  report("degenerate.scene", hits, ours_bad + bad_pixels, naive_nan, "normalize_plus_1e-4");
  EXPECT_GT(hits, 0);
  EXPECT_EQ(ours_bad, 0);
  EXPECT_EQ(bad_pixels, 0);
  EXPECT_GT(naive_nan, 0);
}

}  // namespace
}  // namespace rayform::stress
