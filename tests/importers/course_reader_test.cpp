// The course .txt reader (importers/course_txt): every grammar construct of
// COURSE_FORMAT.md parsed from inline text with parse_course_scene(), and
// every error reported as "file:line:column: <what was expected>".
#include "rayform/importers/course_txt/course_reader.h"
#include "rayform/image/image.h"
#include "rayform/render/render.h"
#include "rayform/base/error.h"
#include "rayform/scene/node_walk.h"
#include "test_importers.h"
#include "test_paths.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <fstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;

const std::string kCamera = "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }\n";

CourseScene parse(const std::string& text, CourseReadOptions options = {}, const std::string& path = "t.txt") {
  return parse_course_scene(text, path, options);
}

// The message of the error parsing `text` throws ("" when it parses).
std::string error_of(const std::string& text, const std::string& path = "t.txt", CourseReadOptions options = {}) {
  try {
    parse_course_scene(text, path, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

using test::where;

// Position just after the last character (where end-of-file errors point).
std::string end_of(const std::string& text, const std::string& path = "t.txt") {
  int line = 1, col = 1;
  for (char c : text) {
    if (c == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return path + ":" + std::to_string(line) + ":" + std::to_string(col);
}

// The error must start with the position and contain every expected fragment.
#define EXPECT_PARSE_ERROR(text, position, ...)                                                     \
  do {                                                                                              \
    std::string msg_ = error_of(text);                                                              \
    ASSERT_FALSE(msg_.empty()) << "no error for:\n" << (text);                                      \
    EXPECT_EQ(msg_.rfind((position) + ": ", 0), 0u)                                                 \
        << "error at the wrong place: " << msg_ << "\nexpected it at " << (position);               \
    for (const char* frag_ : {__VA_ARGS__})                                                         \
      EXPECT_NE(msg_.find(frag_), std::string::npos) << "'" << frag_ << "' missing from: " << msg_; \
  } while (0)

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

void write_picture(const fs::path& p) {
  Image img(2, 2, 3, 0.5f);
  write_image(p.string(), img);
}

// Object-to-world matrices of the shape nodes, depth first.
std::vector<mat4> shape_matrices(const Scene& s) {
  std::vector<mat4> out;
  for_each_shape_node(s, [&](const Node&, const mat4& m) { out.push_back(m); });
  return out;
}

std::vector<const Node*> shape_nodes(const Scene& s) {
  std::vector<const Node*> out;
  for_each_shape_node(s, [&](const Node& n, const mat4&) { out.push_back(&n); });
  return out;
}

// Float rounding of sin/cos of radians(deg) and of the matrix products:
// a few ulps of 1; 1e-6 is far below any wrong rotation or order.
constexpr float kTol = 1e-6f;

void expect_point(const mat4& m, vec3 p, vec3 want, const std::string& what) {
  vec3 got = transform_point(m, p);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(got[k], want[k], kTol * std::max(1.f, std::abs(want[k]))) << what << " [" << k << "]";
}

mat4 single_transform(const std::string& xforms) {
  std::string text = kCamera + "Group { numObjects 1 Transform { " + xforms + " Sphere { center 0 0 0 radius 1 } } }\n";
  CourseScene cs = parse(text);
  std::vector<mat4> m = shape_matrices(cs.scene);
  EXPECT_EQ(m.size(), 1u);
  return m.empty() ? mat4(1.f) : m[0];
}

// ---------------------------------------------------------------- grammar

TEST(CourseReader, Camera) {
  CourseScene cs = parse(
      "PerspectiveCamera {\n  center 1 2 3\n  direction 0 0 -2\n  up 0 1 0.5\n  angle 45\n}\n"
      "Group { numObjects 0 }\n");
  ASSERT_EQ(cs.scene.cameras.size(), 1u);
  const Camera& c = cs.scene.cameras[0];
  EXPECT_EQ(c.center, vec3(1, 2, 3));
  EXPECT_EQ(c.direction, vec3(0, 0, -2));
  EXPECT_EQ(c.up, vec3(0, 1, 0.5f));
  EXPECT_EQ(c.fov_deg, 45.f);
  EXPECT_EQ(c.projection, Camera::Projection::perspective);
  EXPECT_EQ(c.aspect, Camera::Aspect::stretch) << "the course stretches non-square images";
  EXPECT_EQ(c.up_vector, Camera::UpVector::orthonormal) << "2012 orthogonalises up";
  EXPECT_EQ(cs.dialect, CourseDialect::v2012);
}

TEST(CourseReader, Camera2019UsesTheRawUp) {
  CourseReadOptions o;
  o.dialect = CourseDialect::v2019;
  CourseScene cs = parse(kCamera + "Group { numObjects 0 }\n", o);
  EXPECT_EQ(cs.dialect, CourseDialect::v2019);
  EXPECT_EQ(cs.scene.cameras.at(0).up_vector, Camera::UpVector::raw);
}

TEST(CourseReader, KeysInAnyOrderAndALaterBlockOverrides) {
  CourseScene cs = parse(
      "PerspectiveCamera { angle 20 up 0 1 0 direction 1 0 0 center 9 9 9 }\n"
      "PerspectiveCamera { angle 60 up 0 0 1 direction 0 1 0 center 4 5 6 }\n"
      "Group { numObjects 1 Sphere { radius 2 center 1 2 3 } }\n");
  ASSERT_EQ(cs.scene.cameras.size(), 1u);
  EXPECT_EQ(cs.scene.cameras[0].center, vec3(4, 5, 6));
  EXPECT_EQ(cs.scene.cameras[0].fov_deg, 60.f);
  ASSERT_EQ(cs.scene.spheres.size(), 1u);
  EXPECT_EQ(cs.scene.spheres[0].center, vec3(1, 2, 3));
  EXPECT_EQ(cs.scene.spheres[0].radius, 2.f);
}

TEST(CourseReader, CommentsAndNumbersTouchingBraces) {
  CourseScene cs = parse("# a scene\n" + kCamera +
                         "Materials { numMaterials 1 Material { diffuseColor 1 0 0 shininess 20} }  # trailing\n"
                         "Group { numObjects 1\n"
                         "  Sphere { center 1 2 3 # radius 9 is commented out\n"
                         "    radius 2}# no space before the comment\n"
                         "}");
  ASSERT_EQ(cs.scene.spheres.size(), 1u);
  EXPECT_EQ(cs.scene.spheres[0].radius, 2.f);
  EXPECT_EQ(cs.scene.materials.at(0).shininess, 20.f);
  // Braces need no white space around them at all.
  CourseScene t = parse(kCamera + "Group{numObjects 1 Transform{Translate 1 2 3 Sphere{center 4 5 6 radius 7}}}");
  ASSERT_EQ(t.scene.spheres.size(), 1u);
  EXPECT_EQ(t.scene.spheres[0].center, vec3(4, 5, 6));
  EXPECT_EQ(t.scene.spheres[0].radius, 7.f);
  expect_point(shape_matrices(t.scene).at(0), vec3(0.f), vec3(1, 2, 3), "Translate touching '{'");
}

TEST(CourseReader, DirectionalAndPointLights) {
  CourseScene cs = parse(kCamera +
                         "Lights { numLights 3\n"
                         "  DirectionalLight { direction -0.2 -0.4 -0.8 color 0.8 0.7 0.6 }\n"
                         "  PointLight { position 0.5 2 1 color 0.9 0.7 0.5 }\n"
                         "  PointLight { color 1 1 1 position 0 20 0 }\n"
                         "}\nGroup { numObjects 0 }\n");
  ASSERT_EQ(cs.scene.lights.size(), 3u);
  const Light& d = cs.scene.lights[0];
  EXPECT_EQ(d.kind, Light::Kind::directional);
  EXPECT_EQ(d.direction, vec3(-0.2f, -0.4f, -0.8f));
  EXPECT_EQ(d.color, vec3(0.8f, 0.7f, 0.6f));
  const Light& p = cs.scene.lights[1];
  EXPECT_EQ(p.kind, Light::Kind::point);
  EXPECT_EQ(p.position, vec3(0.5f, 2, 1));
  EXPECT_EQ(p.color, vec3(0.9f, 0.7f, 0.5f));
  EXPECT_EQ(p.falloff, 0.f);
  EXPECT_EQ(cs.scene.lights[2].position, vec3(0, 20, 0));
}

TEST(CourseReader, FalloffAttenuatesOnlyIn2019) {
  const std::string text = kCamera + "Lights { numLights 1 PointLight { position 0 5 5 color 1 1 1 falloff 0.25 } }\n" +
                           "Group { numObjects 0 }\n";
  CourseScene detected = parse(text);
  EXPECT_EQ(detected.dialect, CourseDialect::v2019) << "falloff selects the 2019 dialect";
  EXPECT_EQ(detected.scene.lights.at(0).falloff, 0.25f);
  CourseReadOptions o;
  o.dialect = CourseDialect::v2012;
  CourseScene forced = parse(text, o);
  EXPECT_EQ(forced.dialect, CourseDialect::v2012);
  EXPECT_EQ(forced.scene.lights.at(0).falloff, 0.f) << "2012 has no attenuation";
}

TEST(CourseReader, DialectDetection) {
  auto dialect = [](const std::string& body) { return parse(kCamera + body + "Group { numObjects 0 }\n").dialect; };
  EXPECT_EQ(dialect(""), CourseDialect::v2012);
  EXPECT_EQ(dialect("# falloff and bump only in a comment\n"), CourseDialect::v2012);
  EXPECT_EQ(dialect("Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 falloff 1 } }\n"),
            CourseDialect::v2019);
  auto dir = test::temp_dir("reader_dialect");
  write_picture(dir / "b.bmp");
  fs::create_directories(dir / "sky");
  for (const char* face : {"right", "left", "up", "down", "front", "back"})
    write_picture(dir / "sky" / (std::string(face) + ".png"));
  std::string path = (dir / "s.txt").string();
  CourseScene bump =
      parse(kCamera + "Materials { numMaterials 1 Material { bump b.bmp } }\nGroup { numObjects 0 }\n", {}, path);
  EXPECT_EQ(bump.dialect, CourseDialect::v2019);
  EXPECT_EQ(bump.scene.materials.at(0).bump_texture, 0);
  CourseScene cube = parse(kCamera + "Background { cubeMap sky }\nGroup { numObjects 0 }\n", {}, path);
  // .png faces are 2019's now that a5 is told apart by its .bmp faces
  // (COURSE_FORMAT.md; course_a5_test.cpp checks the others).
  EXPECT_EQ(cube.dialect, CourseDialect::v2019) << "a cube map of .png faces";
  EXPECT_EQ(cube.scene.background.cube_map_dir, "sky");
  for (int i = 0; i < 6; ++i) EXPECT_NE(cube.scene.background.cube_map[i], invalid);
  fs::remove_all(dir);
}

TEST(CourseReader, BackgroundAndItsDefaults) {
  CourseScene none = parse(kCamera + "Group { numObjects 0 }\n");
  EXPECT_EQ(none.scene.background.color, vec3(0.5f));
  EXPECT_EQ(none.scene.background.ambient, vec3(0.f));
  CourseScene colour = parse(kCamera + "Background { color 0.1 0.2 0.7 }\nGroup { numObjects 0 }\n");
  EXPECT_EQ(colour.scene.background.color, vec3(0.1f, 0.2f, 0.7f));
  EXPECT_EQ(colour.scene.background.ambient, vec3(0.f));
  CourseScene ambient = parse(kCamera + "Background { ambientLight 0.2 0.2 0.2 }\nGroup { numObjects 0 }\n");
  EXPECT_EQ(ambient.scene.background.color, vec3(0.5f));
  EXPECT_EQ(ambient.scene.background.ambient, vec3(0.2f));
  CourseScene both = parse(kCamera + "Background { ambientLight 0.1 0.1 0.1 color 0 0 0 }\nGroup { numObjects 0 }\n");
  EXPECT_EQ(both.scene.background.color, vec3(0.f));
  EXPECT_EQ(both.scene.background.ambient, vec3(0.1f));
}

TEST(CourseReader, MaterialsAndTheirDefaults) {
  auto dir = test::temp_dir("reader_materials");
  write_picture(dir / "wood.bmp");
  std::string path = (dir / "s.txt").string();
  CourseScene cs = parse(kCamera +
                             "Materials { numMaterials 4\n"
                             "  Material { }\n"
                             "  PhongMaterial { diffuseColor 0.2 0.8 0.2 specularColor 0.7 0.9 0.7 shininess 20 }\n"
                             "  Material { texture wood.bmp refractionIndex 1.5 }\n"
                             "  PhongMaterial { texture wood.bmp diffuseColor 1 0 0 }\n"
                             "}\nGroup { numObjects 0 }\n",
                         {}, path);
  const auto& m = cs.scene.materials;
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].diffuse, vec3(1.f));
  EXPECT_EQ(m[0].specular, vec3(0.f));
  EXPECT_EQ(m[0].shininess, 0.f);
  EXPECT_EQ(m[0].diffuse_texture, invalid);
  EXPECT_EQ(m[1].diffuse, vec3(0.2f, 0.8f, 0.2f));
  EXPECT_EQ(m[1].specular, vec3(0.7f, 0.9f, 0.7f));
  EXPECT_EQ(m[1].shininess, 20.f);
  EXPECT_EQ(m[2].refraction_index, 1.5f);
  ASSERT_EQ(cs.scene.textures.size(), 1u) << "one picture named twice is one texture";
  EXPECT_EQ(m[2].diffuse_texture, 0);
  EXPECT_EQ(m[3].diffuse_texture, 0);
  EXPECT_FALSE(m[3].texture_modulates) << "course: the texel replaces the diffuse colour";
  const Texture& t = cs.scene.textures[0];
  EXPECT_EQ(t.lookup, Texture::Lookup::course);
  EXPECT_EQ(t.wrap_u, Texture::Wrap::clamp);
  EXPECT_FALSE(t.srgb) << "course colours are raw";
  EXPECT_TRUE(fs::equivalent(t.path, dir / "wood.bmp")) << t.path;
  fs::remove_all(dir);
}

TEST(CourseReader, NestedGroupsAndObjectCounts) {
  CourseScene cs = parse(kCamera +
                         "Materials { numMaterials 2 Material { } Material { } }\n"
                         "Group { numObjects 3\n"
                         "  MaterialIndex 0\n"
                         "  Sphere { center 0 0 0 radius 1 }\n"
                         "  Group { numObjects 2\n"
                         "    MaterialIndex 1\n"
                         "    Plane { normal 0 1 0 offset -2 }\n"
                         "    Group { numObjects 1 Triangle { vertex0 0 0 0 vertex1 1 0 0 vertex2 0 1 0 } }\n"
                         "  }\n"
                         "  MaterialIndex 0\n"
                         "  Sphere { center 5 0 0 radius 1 }\n"
                         "}\n");
  const Scene& s = cs.scene;
  ASSERT_NE(s.root, invalid);
  const Node& root = s.nodes[s.root];
  EXPECT_EQ(root.kind, Node::Kind::group);
  ASSERT_EQ(root.children.size(), 3u) << "numObjects counts objects, not MaterialIndex lines";
  const Node& inner = s.nodes[root.children[1]];
  EXPECT_EQ(inner.kind, Node::Kind::group);
  ASSERT_EQ(inner.children.size(), 2u);
  EXPECT_EQ(s.nodes[inner.children[1]].kind, Node::Kind::group);
  std::vector<const Node*> shapes = shape_nodes(s);
  ASSERT_EQ(shapes.size(), 4u);
  EXPECT_EQ(shapes[0]->shape_kind, ShapeKind::sphere);
  EXPECT_EQ(shapes[1]->shape_kind, ShapeKind::plane);
  EXPECT_EQ(shapes[2]->shape_kind, ShapeKind::triangle);
  EXPECT_EQ(shapes[3]->shape_kind, ShapeKind::sphere);
  EXPECT_EQ(shapes[0]->material, 0);
  EXPECT_EQ(shapes[1]->material, 1);
  EXPECT_EQ(shapes[2]->material, 1) << "in force in a group nested deeper";
  EXPECT_EQ(shapes[3]->material, 0);
}

// Nesting is limited to the Scene's max_node_depth: the deepest allowed
// loads, one level more is an error at the Transform that crosses it, and a
// hostile file nested 100000 deep fails the same way instead of exhausting the stack.
std::string nested_transforms(int levels) {
  std::string text = kCamera + "Group { numObjects 1\n";
  for (int i = 0; i < levels; ++i) text += "Transform { Translate 1 0 0\n";
  text += "Sphere { center 0 0 0 radius 1 }\n";
  for (int i = 0; i < levels; ++i) text += "}\n";
  return text + "}\n";
}

TEST(CourseReader, NestingDepthIsLimited) {
  // Group (1) + transforms + sphere: max_node_depth - 2 transforms fill the Scene.
  CourseScene cs = parse(nested_transforms(max_node_depth - 2));
  std::vector<mat4> m = shape_matrices(cs.scene);
  ASSERT_EQ(m.size(), 1u);
  expect_point(m[0], vec3(0.f), vec3(float(max_node_depth - 2), 0.f, 0.f), "translations summed over every level");

  std::string deeper = nested_transforms(max_node_depth - 1);
  EXPECT_PARSE_ERROR(deeper, where(deeper, "Transform", max_node_depth - 1), "nested too deeply", "at most 256 levels");
  std::string hostile = nested_transforms(100000);
  EXPECT_PARSE_ERROR(hostile, where(hostile, "Transform", max_node_depth - 1), "nested too deeply");
}

TEST(CourseReader, MaterialIndexStaysInForceAcrossGroups) {
  CourseScene cs = parse(kCamera +
                         "Materials { numMaterials 3 Material { } Material { } Material { } }\n"
                         "Group { numObjects 3\n"
                         "  Sphere { center 0 0 0 radius 1 }\n"
                         "  Group { numObjects 1 MaterialIndex 2 Sphere { center 1 0 0 radius 1 } }\n"
                         "  Transform { Translate 1 0 0 Sphere { center 2 0 0 radius 1 } }\n"
                         "}\n");
  std::vector<const Node*> shapes = shape_nodes(cs.scene);
  ASSERT_EQ(shapes.size(), 3u);
  EXPECT_EQ(shapes[0]->material, invalid) << "before any MaterialIndex: the default material";
  EXPECT_EQ(shapes[1]->material, 2);
  EXPECT_EQ(shapes[2]->material, 2) << "set in a nested group, still in force after it and under a Transform";
}

TEST(CourseReader, SphereAndPlane) {
  CourseScene cs = parse(
      kCamera + "Group { numObjects 2 Sphere { center 1 -2 3.5 radius 0.75 } Plane { normal 0 2 0 offset -4 } }\n");
  ASSERT_EQ(cs.scene.spheres.size(), 1u);
  EXPECT_EQ(cs.scene.spheres[0].center, vec3(1, -2, 3.5f));
  EXPECT_EQ(cs.scene.spheres[0].radius, 0.75f);
  ASSERT_EQ(cs.scene.planes.size(), 1u);
  // n . p = d with n as written: the same plane y = -2, normalised together
  // (EXPECT_FLOAT_EQ: within 4 ulps, the rounding of the division by |n|).
  const Plane& p = cs.scene.planes[0];
  EXPECT_FLOAT_EQ(p.offset / glm::length(p.normal), -2.f);
  EXPECT_FLOAT_EQ(p.normal.y / glm::length(p.normal), 1.f);
}

TEST(CourseReader, Triangle) {
  CourseScene cs = parse(kCamera + "Group { numObjects 1 Triangle { vertex2 0 1 0 vertex0 0 0 0 vertex1 1 0 0 } }\n");
  ASSERT_EQ(cs.scene.triangles.size(), 1u);
  const auto& v = cs.scene.triangles[0].vertices;
  EXPECT_EQ(v[0], vec3(0, 0, 0));
  EXPECT_EQ(v[1], vec3(1, 0, 0));
  EXPECT_EQ(v[2], vec3(0, 1, 0));
}

// ---------------------------------------------------------------- transforms

TEST(CourseReader, ScaleUniformScaleTranslate) {
  expect_point(single_transform("Scale 2 3 4"), vec3(1, 1, 1), vec3(2, 3, 4), "Scale");
  expect_point(single_transform("UniformScale 3"), vec3(1, -1, 2), vec3(3, -3, 6), "UniformScale");
  expect_point(single_transform("Translate 1 2 3"), vec3(0.f), vec3(1, 2, 3), "Translate");
  expect_point(single_transform("Translate 1 2 3"), vec3(1, 1, 1), vec3(2, 3, 4), "Translate");
}

TEST(CourseReader, AxisRotationsAreRightHandedDegrees) {
  expect_point(single_transform("XRotate 90"), vec3(0, 1, 0), vec3(0, 0, 1), "XRotate y->z");
  expect_point(single_transform("YRotate 90"), vec3(0, 0, 1), vec3(1, 0, 0), "YRotate z->x");
  expect_point(single_transform("ZRotate 90"), vec3(1, 0, 0), vec3(0, 1, 0), "ZRotate x->y");
  expect_point(single_transform("ZRotate 30"), vec3(1, 0, 0), vec3(std::cos(pi / 6), std::sin(pi / 6), 0),
               "ZRotate 30");
  expect_point(single_transform("XRotate -90"), vec3(0, 1, 0), vec3(0, 0, -1), "XRotate -90");
}

TEST(CourseReader, RotateNormalisesItsAxis) {
  // 90 degrees about (1, 1, 0)/sqrt2: z -> (1, -1, 0)/sqrt2 (Rodrigues: k x z).
  mat4 m = single_transform("Rotate { 1 1 0 90 }");
  expect_point(m, vec3(0, 0, 1), vec3(1, -1, 0) / std::sqrt(2.f), "Rotate about (1,1,0)");
  expect_point(m, vec3(2, 2, 0), vec3(2, 2, 0), "points on the axis stay");
  // A long axis is the same rotation (an un-normalised axis would scale).
  mat4 z = single_transform("Rotate { 0 0 5 90 }");
  expect_point(z, vec3(1, 0, 0), vec3(0, 1, 0), "Rotate about (0,0,5)");
  expect_point(z, vec3(0, 0, 1), vec3(0, 0, 1), "axis unchanged, not scaled");
}

TEST(CourseReader, Matrix4fIsReadColumnByColumn) {
  // Numbers 13-15 are the translation.
  mat4 t = single_transform("Matrix4f { 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1 }");
  expect_point(t, vec3(0.f), vec3(5, 6, 7), "translation column");
  // The first four numbers are the image of x: here a ZRotate 90.
  mat4 r = single_transform("Matrix4f { 0 1 0 0  -1 0 0 0  0 0 1 0  0 0 0 1 }");
  expect_point(r, vec3(1, 0, 0), vec3(0, 1, 0), "first column");
  expect_point(r, vec3(0, 1, 0), vec3(-1, 0, 0), "second column");
}

TEST(CourseReader, TransformCompositionOrder) {
  // The others right-multiply: the first listed acts last on the object.
  expect_point(single_transform("Translate 1 0 0 Scale 2 2 2"), vec3(1, 0, 0), vec3(3, 0, 0), "T S");
  expect_point(single_transform("Scale 2 2 2 Translate 1 0 0"), vec3(1, 0, 0), vec3(4, 0, 0), "S T");
  expect_point(single_transform("Translate 1 0 0 ZRotate 90"), vec3(1, 0, 0), vec3(1, 1, 0), "T Rz");
  expect_point(single_transform("ZRotate 90 Translate 1 0 0"), vec3(1, 0, 0), vec3(0, 2, 0), "Rz T");
  // Matrix4f left-multiplies: M := A M.
  const char* scale2 = "Matrix4f { 2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1 }";
  expect_point(single_transform(std::string("Translate 1 0 0 ") + scale2), vec3(0.f), vec3(2, 0, 0),
               "T then Matrix4f: A T");
  const char* move5 = "Matrix4f { 1 0 0 0  0 1 0 0  0 0 1 0  5 0 0 1 }";
  expect_point(single_transform(std::string(move5) + " Scale 2 2 2"), vec3(1, 0, 0), vec3(7, 0, 0),
               "Matrix4f then S: A S");
  expect_point(single_transform(std::string("Scale 2 2 2 ") + move5), vec3(1, 0, 0), vec3(7, 0, 0),
               "S then Matrix4f: A S");
  // scene04's chain, against glm.
  mat4 want = glm::translate(mat4(1.f), vec3(4, 3, 1));
  want = glm::rotate(want, radians(10.f), vec3(1, 0, 0));
  want = glm::rotate(want, radians(20.f), vec3(0, 1, 0));
  want = glm::rotate(want, radians(30.f), vec3(0, 0, 1));
  want = glm::scale(want, vec3(2, 0.5f, 3));
  mat4 got = single_transform("Translate 4 3 1 XRotate 10 YRotate 20 ZRotate 30 Scale 2 0.5 3");
  for (vec3 p : {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), vec3(1, 2, 3)})
    expect_point(got, p, transform_point(want, p), "scene04 chain");
}

TEST(CourseReader, NestedTransformsCompose) {
  CourseScene cs = parse(kCamera +
                         "Group { numObjects 1 Transform { Translate 0 1 0\n"
                         "  Transform { Scale 2 2 2 Sphere { center 0 0 0 radius 1 } } } }\n");
  std::vector<mat4> m = shape_matrices(cs.scene);
  ASSERT_EQ(m.size(), 1u);
  expect_point(m[0], vec3(1, 0, 0), vec3(2, 1, 0), "outer T, inner S");
}

// ---------------------------------------------------------------- meshes

// Two faces meeting at the origin: A = (v1 v2 v3) in z = 0 with raw cross
// product (0, 0, 16); B = (v1 v4 v5) in x = 0 with raw cross product (1, 0, 0).
// vn lines that must be ignored; a quad; and no newline at the end.
const char* kMeshObj =
    "# test mesh\n"
    "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 0 1 0\nv 0 0 1\n"
    "v 10 0 0\nv 11 0 0\nv 11 1 0\nv 10 1 0\n"
    "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
    "vn 0 1 0\nvn 1 1 1\n"
    "f 1/1/1 2/2/1 3/3/2\n"
    "f 1/1/2 4/2/2 5/3/2\n"
    "f 6/1/1 7/2/1 8/4/1 9/3/1";

std::vector<vec3> normals_at(const Mesh& m, vec3 position) {
  std::vector<vec3> out;
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (m.positions[i] == position) out.push_back(m.normals.at(i));
  return out;
}

void expect_unit_near(vec3 got, vec3 want_unnormalised, const std::string& what) {
  vec3 want = glm::normalize(want_unnormalised);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], kTol) << what << " [" << k << "]";
}

TEST(CourseReader, TriangleMeshNormalRulesOfBothDialects) {
  auto dir = test::temp_dir("reader_mesh");
  write_file(dir / "m.obj", kMeshObj);
  std::string path = (dir / "s.txt").string();
  std::string text = kCamera + "Group { numObjects 1 TriangleMesh { obj_file m.obj } }\n";
  for (CourseDialect d : {CourseDialect::v2012, CourseDialect::v2019}) {
    CourseReadOptions o;
    o.dialect = d;
    CourseScene cs = parse(text, o, path);
    ASSERT_EQ(cs.scene.meshes.size(), 1u);
    const Mesh& m = cs.scene.meshes[0];
    std::string name = d == CourseDialect::v2012 ? "2012" : "2019";
    EXPECT_EQ(m.triangle_count(), 4u) << name << ": the quad is two triangles";
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size()) << "texture coordinates are kept";
    // The shared corner: area-weighted (2012) or unit (2019) face normals summed.
    std::vector<vec3> n0 = normals_at(m, vec3(0.f));
    ASSERT_FALSE(n0.empty());
    for (vec3 n : n0)
      expect_unit_near(n, d == CourseDialect::v2012 ? vec3(1, 0, 16) : vec3(1, 0, 1), name + " shared vertex");
    for (vec3 n : normals_at(m, vec3(4, 0, 0))) expect_unit_near(n, vec3(0, 0, 1), name + " face A only (vn ignored)");
    for (vec3 n : normals_at(m, vec3(0, 0, 1))) expect_unit_near(n, vec3(1, 0, 0), name + " face B only (vn ignored)");
    for (vec3 n : normals_at(m, vec3(11, 1, 0))) expect_unit_near(n, vec3(0, 0, 1), name + " quad corner (last line)");
    // uv of the corner (11, 1, 0) is vt 4 = (1, 1).
    for (size_t i = 0; i < m.positions.size(); ++i) {
      if (m.positions[i] != vec3(11, 1, 0)) continue;
      EXPECT_EQ(m.uvs[i], vec2(1, 1));
    }
  }
  fs::remove_all(dir);
}

TEST(CourseReader, RelativePathsResolveBesideTheSceneThenTheWorkingDirectory) {
  auto scene_dir = test::temp_dir("reader_paths_scene");
  auto cwd_dir = test::temp_dir("reader_paths_cwd");
  write_file(scene_dir / "beside.obj", kMeshObj);
  write_file(cwd_dir / "incwd.obj", kMeshObj);
  fs::path old = fs::current_path();
  fs::current_path(cwd_dir);
  std::string path = (scene_dir / "s.txt").string();
  std::string err;
  try {
    CourseScene cs = parse(
        kCamera + "Group { numObjects 2 TriangleMesh { obj_file beside.obj } TriangleMesh { obj_file incwd.obj } }\n",
        {}, path);
    EXPECT_EQ(cs.scene.meshes.size(), 2u);
  } catch (const Error& e) {
    err = e.what();
  }
  fs::current_path(old);
  EXPECT_EQ(err, "");
  fs::remove_all(scene_dir);
  fs::remove_all(cwd_dir);
}

TEST(CourseReader, NoLightsShowsTheDiffuseColour) {
  // COURSE_FORMAT.md: "numLights 0 makes the ambient light (1,1,1), so each
  // pixel shows its material's diffuse colour".
  CourseScene cs = parse(kCamera +
                         "Lights { numLights 0 }\n"
                         "Materials { numMaterials 1 Material { diffuseColor 0.25 0.5 0.75 } }\n"
                         "Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }\n");
  PreparedScene p = prepare_scene(cs.scene);
  RenderOptions o;
  o.width = o.height = 3;
  RenderResult r = render(p, o);
  const float* c = r.color.at(1, 1);
  EXPECT_EQ(vec3(c[0], c[1], c[2]), vec3(0.25f, 0.5f, 0.75f)) << "got " << c[0] << " " << c[1] << " " << c[2];
}

TEST(CourseReader, WarnsAboutASecondTopLevelGroup) {
  CourseScene cs = parse(kCamera + "Group { numObjects 0 }\nGroup { numObjects 1 Sphere { radius 1 } }\n");
  EXPECT_EQ(shape_nodes(cs.scene).size(), 1u) << "the later Group replaces the first";
  ASSERT_FALSE(cs.warnings.empty());
  EXPECT_NE(cs.warnings[0].find("t.txt:3:1"), std::string::npos) << cs.warnings[0];
}

TEST(CourseReader, ReadsTheCourseScenesFromFiles) {
  RAYFORM_REQUIRE_SHARED();
  CourseScene cs = read_course_scene((test::shared_dir() / "course/2012/scene04_axes.txt").string());
  EXPECT_EQ(cs.scene.meshes.size(), 1u) << "cube.obj read once for its four instances";
  EXPECT_EQ(shape_nodes(cs.scene).size(), 4u);
  EXPECT_EQ(cs.scene.materials.size(), 4u);
}

// ---------------------------------------------------------------- errors

TEST(CourseReaderErrors, TruncatedFile) {
  std::string t1 = kCamera + "Group { numObjects 1\n  Sphere { center 0 0";
  EXPECT_PARSE_ERROR(t1, end_of(t1), "unexpected end of file", "expected a number");
  std::string t2 = kCamera + "Group { numObjects 1\n  Sphere { center 0 0 0 radius 1 }\n";
  EXPECT_PARSE_ERROR(t2, end_of(t2), "unexpected end of file", "'}' to close Group opened at 2:1");
  std::string t3 = kCamera + "Materials { numMaterials 1 Material { diffuseColor 1 0 0\n";
  EXPECT_PARSE_ERROR(t3, end_of(t3), "unexpected end of file", "'}' to close Material");
  std::string t4 = "PerspectiveCamera {";
  EXPECT_PARSE_ERROR(t4, end_of(t4), "unexpected end of file", "'}' to close PerspectiveCamera");
  std::string t5 = kCamera + "Group";
  EXPECT_PARSE_ERROR(t5, end_of(t5), "unexpected end of file", "'{'");
}

TEST(CourseReaderErrors, UnknownKeywords) {
  std::string top = kCamera + "Lightz { numLights 0 }\n";
  EXPECT_PARSE_ERROR(top, where(top, "Lightz"), "expected PerspectiveCamera, Lights, Background, Materials or Group");
  std::string key = kCamera + "Group { numObjects 1\n  Sphere { centre 0 0 0 radius 1 } }\n";
  EXPECT_PARSE_ERROR(key, where(key, "centre"), "center, radius", "Sphere");
  std::string cam = "PerspectiveCamera { center 0 0 10 fov 30 }\n";
  EXPECT_PARSE_ERROR(cam, where(cam, "fov"), "center, direction, up, angle");
  std::string obj = kCamera + "Group { numObjects 1\n    Cube { size 1 } }\n";
  EXPECT_PARSE_ERROR(obj, where(obj, "Cube"), "expected an object", "Sphere");
  std::string light = kCamera + "Lights { numLights 1\n SpotLight { } }\n";
  EXPECT_PARSE_ERROR(light, where(light, "SpotLight"), "DirectionalLight, PointLight");
  std::string mat = kCamera + "Materials { numMaterials 1\n  Material { diffuse 1 0 0 } }\n";
  EXPECT_PARSE_ERROR(mat, where(mat, "diffuse "), "diffuseColor", "specularColor", "shininess");
  std::string bg = kCamera + "Background { colour 1 1 1 }\n";
  EXPECT_PARSE_ERROR(bg, where(bg, "colour"), "color, ambientLight");
  std::string nomat = kCamera + "Materials { numMaterials 1\n  Lambert { } }\n";
  EXPECT_PARSE_ERROR(nomat, where(nomat, "Lambert"), "Material, PhongMaterial");
}

TEST(CourseReaderErrors, UnknownWordInsideATransformNamesTheTransforms) {
  // Inside a Transform the expected words are the transform kinds or one
  // object; MaterialIndex is not allowed there.
  std::string t = kCamera + "Group { numObjects 1 Transform {\n  Shear 1 2 Sphere { radius 1 } } }\n";
  EXPECT_PARSE_ERROR(t, where(t, "Shear"), "Scale", "Translate", "Rotate", "Matrix4f");
  std::string m = error_of(t);
  EXPECT_EQ(m.find("MaterialIndex"), std::string::npos) << "MaterialIndex is not allowed in a Transform: " << m;
}

TEST(CourseReaderErrors, MissingOpeningBraceOrCountKeyword) {
  std::string a = kCamera + "Group { numObjects 1\n  Sphere center 0 0 0 }\n";
  EXPECT_PARSE_ERROR(a, where(a, "center 0 0 0 }"), "expected '{' in Sphere", "found 'center'");
  std::string b = kCamera + "Group {\n  Sphere { radius 1 } }\n";
  EXPECT_PARSE_ERROR(b, where(b, "Sphere"), "expected 'numObjects' in Group", "found 'Sphere'");
  std::string c = kCamera + "Lights { DirectionalLight { } }\n";
  EXPECT_PARSE_ERROR(c, where(c, "DirectionalLight"), "expected 'numLights' in Lights");
  std::string d = kCamera + "Materials { Material { } }\n";
  EXPECT_PARSE_ERROR(d, where(d, "Material {"), "expected 'numMaterials' in Materials");
}

TEST(CourseReaderErrors, WrongCounts) {
  std::string few = kCamera + "Group { numObjects 2\n  Sphere { radius 1 }\n}\n";
  EXPECT_PARSE_ERROR(few, where(few, "2\n"), "numObjects is 2", "1");
  std::string many = kCamera + "Group { numObjects 1\n  Sphere { radius 1 }\n  Sphere { radius 2 }\n}\n";
  EXPECT_PARSE_ERROR(many, where(many, "Sphere", 2), "more objects than numObjects 1");
  std::string mats = kCamera + "Materials { numMaterials 3\n  Material { } Material { } }\nGroup { numObjects 0 }\n";
  EXPECT_PARSE_ERROR(mats, where(mats, "3\n"), "numMaterials is 3", "2 materials");
  std::string mats_many = kCamera + "Materials { numMaterials 1\n  Material { }\n  Material { } }\n";
  EXPECT_PARSE_ERROR(mats_many, where(mats_many, "Material {", 2), "more materials than numMaterials 1");
  std::string lights = kCamera + "Lights { numLights 2\n  DirectionalLight { direction 0 0 -1 color 1 1 1 } }\n";
  EXPECT_PARSE_ERROR(lights, where(lights, "2\n"), "numLights is 2", "1 lights");
  std::string lights_many = kCamera + "Lights { numLights 0\n  PointLight { position 0 0 0 color 1 1 1 } }\n";
  EXPECT_PARSE_ERROR(lights_many, where(lights_many, "PointLight"), "more lights than numLights 0");
  std::string neg = kCamera + "Group { numObjects -1 }\n";
  EXPECT_PARSE_ERROR(neg, where(neg, "-1 }"), "expected a count", "-1");
  std::string frac = kCamera + "Group { numObjects 1.5 }\n";
  EXPECT_PARSE_ERROR(frac, where(frac, "1.5"), "expected a whole number", "1.5");
  std::string word = kCamera + "Materials { numMaterials two }\n";
  EXPECT_PARSE_ERROR(word, where(word, "two"), "expected a whole number", "two");
}

TEST(CourseReaderErrors, MaterialIndexOutOfRange) {
  // k must be < numMaterials (the reference's check is off by one).
  std::string t = kCamera +
                  "Materials { numMaterials 2 Material { } Material { } }\n"
                  "Group { numObjects 1\n  MaterialIndex 2\n  Sphere { radius 1 } }\n";
  EXPECT_PARSE_ERROR(t, where(t, "2\n  Sphere"), "MaterialIndex 2 is out of range", "2 materials");
  std::string none = kCamera + "Group { numObjects 1 MaterialIndex 0 Sphere { radius 1 } }\n";
  EXPECT_PARSE_ERROR(none, where(none, "0 Sphere"), "MaterialIndex 0 is out of range", "0 materials");
  std::string ok = kCamera +
                   "Materials { numMaterials 2 Material { } Material { } }\n"
                   "Group { numObjects 1 MaterialIndex 1 Sphere { radius 1 } }\n";
  EXPECT_EQ(error_of(ok), "");
  std::string neg = kCamera + "Group { numObjects 1 MaterialIndex -1 Sphere { radius 1 } }\n";
  EXPECT_PARSE_ERROR(neg, where(neg, "-1 Sphere"), "expected a count");
}

TEST(CourseReaderErrors, MissingFiles) {
  auto dir = test::temp_dir("reader_missing");
  std::string path = (dir / "s.txt").string();
  std::string mesh = kCamera + "Group { numObjects 1\n  TriangleMesh { obj_file nothere.obj } }\n";
  std::string m = error_of(mesh, path);
  EXPECT_EQ(m.rfind(where(mesh, "nothere.obj", 1, path) + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("cannot find mesh file 'nothere.obj'"), std::string::npos) << m;
  std::string tex = kCamera + "Materials { numMaterials 1\n  Material { texture tex/nothere.bmp } }\n";
  m = error_of(tex, path);
  EXPECT_EQ(m.rfind(where(tex, "tex/nothere.bmp", 1, path) + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("cannot find texture 'tex/nothere.bmp'"), std::string::npos) << m;
  std::string cube = kCamera + "Background { cubeMap nosky }\n";
  m = error_of(cube, path);
  EXPECT_EQ(m.rfind(where(cube, "nosky", 1, path) + ": ", 0), 0u) << m;
  fs::create_directories(dir / "halfsky");
  write_picture(dir / "halfsky" / "right.png");
  std::string half = kCamera + "Background { cubeMap halfsky }\n";
  m = error_of(half, path);
  EXPECT_EQ(m.rfind(where(half, "halfsky", 1, path) + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("left.png"), std::string::npos) << m;
  fs::remove_all(dir);
}

TEST(CourseReaderErrors, BadMeshFiles) {
  auto dir = test::temp_dir("reader_badmesh");
  std::string path = (dir / "s.txt").string();
  write_file(dir / "empty.obj", "# no faces\nv 0 0 0\n");
  write_file(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  for (const char* name : {"empty.obj", "range.obj"}) {
    std::string t = kCamera + "Group { numObjects 1\n  TriangleMesh {\n    obj_file " + name + " } }\n";
    std::string m = error_of(t, path);
    EXPECT_EQ(m.rfind(where(t, name, 1, path) + ": ", 0), 0u) << m;
    EXPECT_NE(m.find("cannot load mesh"), std::string::npos) << m;
    EXPECT_NE(m.find(name), std::string::npos) << m;
  }
  std::string nofile = kCamera + "Group { numObjects 1\n  TriangleMesh { } }\n";
  EXPECT_PARSE_ERROR(nofile, where(nofile, "TriangleMesh"), "obj_file");
  fs::remove_all(dir);
}

TEST(CourseReaderErrors, NonNumericNumbers) {
  std::string a = kCamera + "Group { numObjects 1\n  Sphere { center 0 zero 0 radius 1 } }\n";
  EXPECT_PARSE_ERROR(a, where(a, "zero"), "expected a number, found 'zero'");
  std::string b = kCamera + "Group { numObjects 1\n  Sphere { center 0 0 0 radius 1.2.3 } }\n";
  EXPECT_PARSE_ERROR(b, where(b, "1.2.3"), "expected a number, found '1.2.3'");
  std::string c = kCamera + "Group { numObjects 1\n  Sphere { center 0 0 radius 1 } }\n";
  EXPECT_PARSE_ERROR(c, where(c, "radius"), "expected a number, found 'radius'");
  std::string d =
      kCamera +
      "Group { numObjects 1 Transform {\n  Matrix4f { 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 } Sphere { radius 1 } } }\n";
  EXPECT_PARSE_ERROR(d, where(d, "} Sphere"), "expected a number, found '}'");
  std::string e = "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30deg }\n";
  EXPECT_PARSE_ERROR(e, where(e, "30deg"), "expected a number, found '30deg'");
}

TEST(CourseReaderErrors, NanAndInfinity) {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e39", "-1e400"}) {
    std::string t = kCamera + "Group { numObjects 1\n  Sphere { center 0 0 " + bad + " radius 1 } }\n";
    std::string pos = where(t, std::string(bad) + " radius");
    EXPECT_PARSE_ERROR(t, pos, "expected a finite number");
    EXPECT_NE(error_of(t).find(bad), std::string::npos) << "names the token";
  }
}

TEST(CourseReaderErrors, InvalidValues) {
  std::string zero = kCamera + "Group { numObjects 1\n  Sphere { center 0 0 0 radius 0 } }\n";
  EXPECT_PARSE_ERROR(zero, where(zero, "Sphere"), "sphere radius must be positive");
  std::string neg = kCamera + "Group { numObjects 1\n  Sphere { radius -2 } }\n";
  EXPECT_PARSE_ERROR(neg, where(neg, "Sphere"), "sphere radius must be positive");
  std::string plane = kCamera + "Group { numObjects 1\n  Plane { normal 0 0 0 offset 1 } }\n";
  EXPECT_PARSE_ERROR(plane, where(plane, "Plane"), "plane normal must not be zero");
  std::string rot = kCamera + "Group { numObjects 1 Transform {\n  Rotate { 0 0 0 45 } Sphere { radius 1 } } }\n";
  EXPECT_PARSE_ERROR(rot, where(rot, "Rotate"), "Rotate axis must not be zero");
  std::string falloff = kCamera + "Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1\n  falloff -1 } }\n";
  EXPECT_PARSE_ERROR(falloff, where(falloff, "-1 }"), "falloff must not be negative");
  std::string dir = "PerspectiveCamera { center 0 0 10 direction 0 0 0 up 0 1 0 angle 30 }\n";
  EXPECT_PARSE_ERROR(dir, where(dir, "PerspectiveCamera"), "direction must not be zero");
  std::string up = "PerspectiveCamera { center 0 0 10 direction 0 2 0 up 0 1 0 angle 30 }\n";
  EXPECT_PARSE_ERROR(up, where(up, "PerspectiveCamera"), "up must not be zero or parallel");
  for (const char* angle : {"0", "180", "-30"}) {
    std::string a = std::string("PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle ") + angle + " }\n";
    EXPECT_PARSE_ERROR(a, where(a, "PerspectiveCamera"), "angle must lie strictly between 0 and 180");
  }
  std::string ldir = kCamera + "Lights { numLights 1\n  DirectionalLight { direction 0 0 0 color 1 1 1 } }\n";
  EXPECT_PARSE_ERROR(ldir, where(ldir, "DirectionalLight"), "light direction must not be zero");
}

TEST(CourseReaderErrors, TransformsHoldExactlyOneObject) {
  std::string none = kCamera + "Group { numObjects 1\n  Transform { Scale 1 1 1 } }\n";
  EXPECT_PARSE_ERROR(none, where(none, "Transform"), "Transform holds no object");
  std::string two = kCamera + "Group { numObjects 1\n  Transform { Sphere { radius 1 }\n    Sphere { radius 2 } } }\n";
  EXPECT_PARSE_ERROR(two, where(two, "Sphere", 2), "exactly one object");
  std::string rot = kCamera + "Group { numObjects 1 Transform {\n  Rotate 0 0 1 45 Sphere { radius 1 } } }\n";
  EXPECT_PARSE_ERROR(rot, where(rot, "0 0 1 45"), "expected '{' in Rotate");
}

TEST(CourseReaderErrors, NoCamera) {
  std::string m = error_of("Group { numObjects 0 }\n", "scenes/x.txt");
  EXPECT_NE(m.find("scenes/x.txt"), std::string::npos) << m;
  EXPECT_NE(m.find("PerspectiveCamera"), std::string::npos) << m;
}

TEST(CourseReaderErrors, ReadingAMissingSceneFile) {
  try {
    read_course_scene("/nonexistent/scene.txt");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.txt"), std::string::npos) << e.what();
  }
}

TEST(CourseReaderErrors, PositionsCountTabsAndCommentsLikeAnyCharacter) {
  // Columns are 1-based byte positions; comments and tabs do not shift lines.
  std::string t = kCamera + "# comment line\nGroup { numObjects 1 # another\n\tSphere {\tradius x } }\n";
  EXPECT_PARSE_ERROR(t, where(t, "x }"), "expected a number, found 'x'");
  EXPECT_EQ(where(t, "x }"), "t.txt:4:18");  // the helper itself, checked once by hand
}

}  // namespace
}  // namespace rayform
