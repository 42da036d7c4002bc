// Scene queries (src/render/scene_intersect.h) over prepared scenes:
// transformed instances (t shared between object and world space, normals by
// the inverse transpose), planes outside the BVH, closest hit across
// instances, any-hit, and the material of each hit (including the course's
// MaterialIndex rule).
#include "rayform/importers/course_txt/course_reader.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/scene/procedural_mesh.h"
#include "test_rays.h"
#include "test_scenes.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace rayform {
namespace {

// A scene built node by node under one root group.
struct Builder {
  Scene s;
  Builder() {
    Camera c;
    c.center = vec3(0, 0, 10);
    c.direction = vec3(0, 0, -1);
    s.cameras.push_back(c);
    s.nodes.push_back(Node{});  // root group
    s.root = 0;
  }
  int add(Node n, int parent) {
    s.nodes.push_back(std::move(n));
    int index = int(s.nodes.size()) - 1;
    s.nodes[parent].children.push_back(index);
    return index;
  }
  int transform(const mat4& m, int parent = 0) {
    Node n;
    n.kind = Node::Kind::transform;
    n.local = m;
    return add(n, parent);
  }
  int shape(ShapeKind kind, int index, int parent = 0, int material = invalid) {
    return add(test::shape_node(kind, index, material), parent);
  }
  int sphere(vec3 c, float r, int parent = 0, int material = invalid) {
    s.spheres.push_back({c, r});
    return shape(ShapeKind::sphere, int(s.spheres.size()) - 1, parent, material);
  }
  int plane(vec3 n, float d, int parent = 0) {
    s.planes.push_back({n, d});
    return shape(ShapeKind::plane, int(s.planes.size()) - 1, parent);
  }
  int triangle(vec3 a, vec3 b, vec3 c, int parent = 0) {
    s.triangles.push_back({{a, b, c}});
    return shape(ShapeKind::triangle, int(s.triangles.size()) - 1, parent);
  }
  int mesh(Mesh m, int parent = 0) {
    s.meshes.push_back(std::move(m));
    return shape(ShapeKind::mesh, int(s.meshes.size()) - 1, parent);
  }
};

using test::make_ray;

// Coordinates here are at most ~10; a few float roundings of the transform
// and its inverse stay below 1e-5, while every mistake tested for (wrong
// matrix order, forward instead of inverse transpose, renormalised direction)
// moves the values by more than 0.1.
constexpr float kTol = 1e-5f;

void expect_vec_near(vec3 got, vec3 want, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], kTol) << what << " component " << k;
}

TEST(SceneIntersect, ScaledTranslatedSphereShareTWithWorldSpace) {
  Builder b;
  // Unit sphere, scaled by 2 then moved to z = -3: the world sphere has
  // centre (0, 0, -3) and radius 2.
  int t = b.transform(glm::scale(glm::translate(mat4(1.f), vec3(0, 0, -3)), vec3(2.f)));
  b.sphere(vec3(0.f), 1.f, t);
  PreparedScene p = prepare_scene(b.s);
  ASSERT_EQ(p.instances.size(), 1u);
  EXPECT_TRUE(p.instances[0].has_transform);
  Hit h;
  Ray r = make_ray({0, 0, 10}, {0, 0, -1});
  ASSERT_TRUE(intersect_scene(p, r, &h));
  EXPECT_NEAR(h.t, 11.f, kTol);
  // A non-unit world direction: t in units of it (the object-space ray is not
  // renormalised, so the same t names the same point).
  Ray r4 = make_ray({0, 0, 10}, {0, 0, -4});
  ASSERT_TRUE(intersect_scene(p, r4, &h));
  EXPECT_NEAR(h.t, 2.75f, kTol);
  SurfacePoint sp = surface_point(p, r4, h);
  expect_vec_near(sp.position, vec3(0, 0, -1), "hit point");
  expect_vec_near(sp.normal, vec3(0, 0, 1), "normal");
  // Off-axis: the hit point lies on the world sphere.
  Ray ro = make_ray({1, 0.5f, 10}, {0, 0, -1});
  ASSERT_TRUE(intersect_scene(p, ro, &h));
  sp = surface_point(p, ro, h);
  EXPECT_NEAR(glm::length(sp.position - vec3(0, 0, -3)), 2.f, kTol);
  expect_vec_near(sp.normal, (sp.position - vec3(0, 0, -3)) / 2.f, "normal is radial");
}

TEST(SceneIntersect, NormalsTransformByTheInverseTranspose) {
  Builder b;
  // Ellipsoid x^2/4 + y^2 + z^2 = 1 (unit sphere scaled by 2 along x).
  int t = b.transform(glm::scale(mat4(1.f), vec3(2, 1, 1)));
  b.sphere(vec3(0.f), 1.f, t);
  PreparedScene p = prepare_scene(b.s);
  Hit h;
  Ray r = make_ray({10, 0.5f, 0}, {-1, 0, 0});
  ASSERT_TRUE(intersect_scene(p, r, &h));
  // x^2 / 4 = 0.75 -> x = sqrt(3).
  EXPECT_NEAR(h.t, 10.f - std::sqrt(3.f), kTol);
  SurfacePoint sp = surface_point(p, r, h);
  expect_vec_near(sp.position, vec3(std::sqrt(3.f), 0.5f, 0), "hit point");
  // Gradient of x^2/4 + y^2: (x/2, 2y) = (sqrt3/2, 1) ~ (sqrt3, 2) / sqrt7.
  // (The forward matrix would give (sqrt3, 0.5) / |.|: x ~ 0.96 instead of 0.65.)
  expect_vec_near(sp.normal, vec3(std::sqrt(3.f), 2.f, 0.f) / std::sqrt(7.f), "inverse-transpose normal");
  EXPECT_NEAR(glm::length(sp.normal), 1.f, kTol);
}

TEST(SceneIntersect, NestedTransformsCompose) {
  Builder b;
  int outer = b.transform(glm::translate(mat4(1.f), vec3(0, 0, -2)));
  int inner = b.transform(glm::scale(mat4(1.f), vec3(0.5f)), outer);
  b.sphere(vec3(0.f), 1.f, inner);
  PreparedScene p = prepare_scene(b.s);
  Hit h;
  ASSERT_TRUE(intersect_scene(p, make_ray({0, 0, 10}, {0, 0, -1}), &h));
  EXPECT_NEAR(h.t, 11.5f, kTol);  // world sphere: centre z = -2, radius 0.5
  // (Scale applied after the translation would put it at z = -1: t = 10.5.)
  EXPECT_FALSE(intersect_scene(p, make_ray({0, 0.6f, 10}, {0, 0, -1}), &h));
}

TEST(SceneIntersect, RotatedTriangleUsesItsFaceNormal) {
  Builder b;
  // XRotate 90 maps (x, y, z) to (x, -z, y): the triangle in z = 0 with face
  // normal +z goes to the plane y = 0 with normal -y.
  int t = b.transform(glm::rotate(mat4(1.f), radians(90.f), vec3(1, 0, 0)));
  b.triangle(vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), t);
  PreparedScene p = prepare_scene(b.s);
  Hit h;
  Ray r = make_ray({0.2f, 5.f, 0.3f}, {0, -1, 0});
  ASSERT_TRUE(intersect_scene(p, r, &h));
  EXPECT_NEAR(h.t, 5.f, kTol);
  SurfacePoint sp = surface_point(p, r, h);
  expect_vec_near(sp.position, vec3(0.2f, 0.f, 0.3f), "hit point");
  expect_vec_near(sp.normal, vec3(0, -1, 0), "face normal, not flipped towards the ray");
  expect_vec_near(sp.geometric_normal, vec3(0, -1, 0), "geometric normal");
  EXPECT_FALSE(sp.has_uv);
  // Outside the rotated triangle (z = 0.8, x = 0.3: x + z > 1).
  EXPECT_FALSE(intersect_scene(p, make_ray({0.3f, 5.f, 0.8f}, {0, -1, 0}), &h));
}

TEST(SceneIntersect, TransformedPlanes) {
  Builder b;
  int up = b.transform(glm::translate(mat4(1.f), vec3(0, 3, 0)));
  b.plane(vec3(0, 1, 0), 0.f, up);  // y = 3
  PreparedScene p = prepare_scene(b.s);
  EXPECT_EQ(p.plane_instances.size(), 1u);
  Hit h;
  Ray r = make_ray({1, 10, 2}, {0, -1, 0});
  ASSERT_TRUE(intersect_scene(p, r, &h));
  EXPECT_NEAR(h.t, 7.f, kTol);
  expect_vec_near(surface_point(p, r, h).normal, vec3(0, 1, 0), "plane normal");

  Builder c;
  int rot = c.transform(glm::rotate(mat4(1.f), radians(90.f), vec3(0, 0, 1)));
  c.plane(vec3(0, 1, 0), 2.f, rot);  // y = 2 rotated: x = -2 with normal -x
  PreparedScene q = prepare_scene(c.s);
  Ray rx = make_ray({5, 0, 0}, {-1, 0, 0});
  ASSERT_TRUE(intersect_scene(q, rx, &h));
  EXPECT_NEAR(h.t, 7.f, kTol);
  expect_vec_near(surface_point(q, rx, h).normal, vec3(-1, 0, 0), "rotated plane normal");
}

TEST(SceneIntersect, InstancedMeshesUnderDifferentTransforms) {
  Builder b;
  b.s.meshes.push_back(make_cube());  // [-1, 1]^3, no normals: face normals
  int left = b.transform(glm::translate(mat4(1.f), vec3(-5, 0, 0)));
  int right = b.transform(glm::scale(glm::translate(mat4(1.f), vec3(5, 0, 0)), vec3(1, 1, 3)));
  b.shape(ShapeKind::mesh, 0, left);
  b.shape(ShapeKind::mesh, 0, right);
  PreparedScene p = prepare_scene(b.s);
  Hit h;
  Ray rl = make_ray({-5, 0.2f, 10}, {0, 0, -1}), rr = make_ray({5, 0.2f, 10}, {0, 0, -2});
  ASSERT_TRUE(intersect_scene(p, rl, &h));
  EXPECT_NEAR(h.t, 9.f, kTol);
  expect_vec_near(surface_point(p, rl, h).normal, vec3(0, 0, 1), "left cube front face");
  ASSERT_TRUE(intersect_scene(p, rr, &h));
  EXPECT_NEAR(h.t, 3.5f, kTol);  // front face at z = 3, direction length 2
  expect_vec_near(surface_point(p, rr, h).position, vec3(5, 0.2f, 3), "right cube hit point");
  // Side face of the stretched cube: x = 6 with a normal that stays +x.
  Ray rs = make_ray({10, 0, 1}, {-1, 0, 0});
  ASSERT_TRUE(intersect_scene(p, rs, &h));
  EXPECT_NEAR(h.t, 4.f, kTol);
  expect_vec_near(surface_point(p, rs, h).normal, vec3(1, 0, 0), "side normal");
  EXPECT_FALSE(intersect_scene(p, make_ray({0, 0, 10}, {0, 0, -1}), &h)) << "between the cubes";
}

TEST(SceneIntersect, MeshNormalsAndUvsAreInterpolated) {
  Builder b;
  b.mesh(make_grid(2, 2));  // [0,1]^2 at z = 0, normals +z, uv = xy
  PreparedScene p = prepare_scene(b.s);
  Hit h;
  Ray r = make_ray({0.3f, 0.7f, 1.f}, {0, 0, -1});
  ASSERT_TRUE(intersect_scene(p, r, &h));
  SurfacePoint sp = surface_point(p, r, h);
  ASSERT_TRUE(sp.has_uv);
  EXPECT_NEAR(sp.uv.x, 0.3f, kTol);
  EXPECT_NEAR(sp.uv.y, 0.7f, kTol);
  expect_vec_near(sp.normal, vec3(0, 0, 1), "grid normal");
  // Icosphere: vertex normals = positions, so the interpolated normal at a hit
  // is close to the radial direction (within the facet's angular size).
  Builder s;
  s.mesh(make_icosphere(3));
  PreparedScene ps = prepare_scene(s.s);
  Ray rr = make_ray({0.3f, 0.2f, 5.f}, {0, 0, -1});
  ASSERT_TRUE(intersect_scene(ps, rr, &h));
  sp = surface_point(ps, rr, h);
  EXPECT_GT(glm::dot(sp.normal, glm::normalize(sp.position)), 0.999f);
  EXPECT_NEAR(glm::length(sp.normal), 1.f, kTol);
}

TEST(SceneIntersect, ClosestHitAcrossInstancesAndPlanes) {
  Builder b;
  b.sphere(vec3(0, 0, -4), 1.f);  // far
  b.plane(vec3(0, 0, 1), -8.f);   // behind everything: z = -8
  b.sphere(vec3(0, 0, 2), 1.f);   // near, added last
  PreparedScene p = prepare_scene(b.s);
  Hit h;
  Ray r = make_ray({0, 0, 10}, {0, 0, -1});
  ASSERT_TRUE(intersect_scene(p, r, &h));
  EXPECT_EQ(h.t, 7.f);
  EXPECT_EQ(p.instances[h.instance].kind, ShapeKind::sphere);
  EXPECT_EQ(p.instances[h.instance].shape, 1);
  // Beside the spheres: the plane.
  Ray side = make_ray({3, 0, 10}, {0, 0, -1});
  ASSERT_TRUE(intersect_scene(p, side, &h));
  EXPECT_EQ(h.t, 18.f);
  EXPECT_EQ(p.instances[h.instance].kind, ShapeKind::plane);
  // A plane in front wins over the spheres.
  Builder c;
  c.sphere(vec3(0, 0, 0), 1.f);
  c.plane(vec3(0, 0, 1), 5.f);
  PreparedScene q = prepare_scene(c.s);
  ASSERT_TRUE(intersect_scene(q, r, &h));
  EXPECT_EQ(h.t, 5.f);
  // tmin / tmax bound the query.
  Ray limited = r;
  limited.tmax = 6.5f;
  EXPECT_FALSE(intersect_scene(p, limited, &h));
  limited.tmin = 7.5f;
  limited.tmax = infinity;
  ASSERT_TRUE(intersect_scene(p, limited, &h));
  EXPECT_EQ(h.t, 9.f);  // far side of the near sphere
}

TEST(SceneIntersect, OccludedSegments) {
  Builder b;
  int t = b.transform(glm::translate(mat4(1.f), vec3(0, 0, -2)));
  b.mesh(make_icosphere(2), t);  // mesh instance under a transform
  b.sphere(vec3(4, 0, 0), 1.f);
  b.plane(vec3(0, 1, 0), -3.f);
  PreparedScene p = prepare_scene(b.s);
  EXPECT_TRUE(occluded(p, make_ray({0, 0, 10}, {0, 0, -1}, 0.f, 20.f)));
  EXPECT_FALSE(occluded(p, make_ray({0, 0, 10}, {0, 0, -1}, 0.f, 8.5f)));  // stops before the mesh (z >= -1)
  EXPECT_TRUE(occluded(p, make_ray({4, 0, 10}, {0, 0, -1}, 0.f, 9.5f)));
  EXPECT_FALSE(occluded(p, make_ray({4, 0, 10}, {0, 0, 1}, 0.f, infinity)));
  EXPECT_TRUE(occluded(p, make_ray({10, 0, 10}, {0, -1, 0}, 0.f, infinity)));  // the plane
  EXPECT_FALSE(occluded(p, make_ray({10, 0, 10}, {0, -1, 0}, 0.f, 2.9f)));
}

TEST(SceneIntersect, HitsCarryTheirNodesMaterial) {
  Builder b;
  b.s.materials.resize(3);
  b.sphere(vec3(-3, 0, 0), 1.f, 0, 2);
  b.sphere(vec3(0, 0, 0), 1.f, 0, invalid);
  b.sphere(vec3(3, 0, 0), 1.f, 0, 0);
  PreparedScene p = prepare_scene(b.s);
  ASSERT_EQ(p.materials.size(), 4u) << "the scene's materials, then the default one";
  auto material_at = [&](float x) {
    Hit h;
    Ray r = make_ray({x, 0, 10}, {0, 0, -1});
    EXPECT_TRUE(intersect_scene(p, r, &h));
    return surface_point(p, r, h).material;
  };
  EXPECT_EQ(material_at(-3.f), 2);
  EXPECT_EQ(material_at(0.f), 3);  // no material: the default, last
  EXPECT_EQ(material_at(3.f), 0);
  const Material& def = p.materials[3];
  EXPECT_EQ(def.diffuse, vec3(1.f));
  EXPECT_EQ(def.specular, vec3(0.f));
}

TEST(SceneIntersect, MaterialIndexRuleOfTheCourseFormat) {
  // MaterialIndex stays in force for later objects, into nested groups, and
  // after a nested group sets another one.
  const char* text = R"(
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Materials { numMaterials 3
  Material { diffuseColor 1 0 0 } Material { diffuseColor 0 1 0 } Material { diffuseColor 0 0 1 } }
Group { numObjects 4
  Sphere { center -6 0 0 radius 1 }
  MaterialIndex 1
  Sphere { center -3 0 0 radius 1 }
  Group { numObjects 2
    Sphere { center 0 0 0 radius 1 }
    MaterialIndex 2
    Transform { Translate 3 0 0 Sphere { center 0 0 0 radius 1 } } }
  Sphere { center 6 0 0 radius 1 }
}
)";
  CourseScene cs = parse_course_scene(text, "inline.txt");
  PreparedScene p = prepare_scene(cs.scene);
  auto material_at = [&](float x) {
    Hit h;
    Ray r = make_ray({x, 0, 10}, {0, 0, -1});
    EXPECT_TRUE(intersect_scene(p, r, &h)) << x;
    return surface_point(p, r, h).material;
  };
  EXPECT_EQ(material_at(-6.f), 3) << "before any MaterialIndex: the default material";
  EXPECT_EQ(material_at(-3.f), 1);
  EXPECT_EQ(material_at(0.f), 1) << "in force inside a nested group";
  EXPECT_EQ(material_at(3.f), 2);
  EXPECT_EQ(material_at(6.f), 2) << "a nested group's MaterialIndex stays in force after it closes";
  EXPECT_EQ(p.materials[2].diffuse, vec3(0, 0, 1));
}

}  // namespace
}  // namespace rayform
