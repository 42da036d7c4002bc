// The course's assignment-5 dialect (a5, COURSE_FORMAT.md "2012 assignment 5"):
// its detection, what the reader makes of its scenes (no highlight, 1 + falloff
// d^2 attenuation, the closest-hit shadow rule, flat normals of small meshes,
// Noise, .bmp cube maps), its errors, and small renders checking each rule's
// value against the formula.
#include "rayform/image/image.h"
#include "rayform/importers/course_txt/course_reader.h"
#include "rayform/importers/scene_io.h"
#include "rayform/pipeline/scene_ready.h"
#include "rayform/importers/scene_writer.h"
#include "rayform/math/perlin_noise.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/base/error.h"
#include "test_importers.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;

const std::string kCamera = "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }\n";
const char* kFaces[6] = {"right", "left", "up", "down", "front", "back"};

CourseScene parse(const std::string& text, std::optional<CourseDialect> dialect = std::nullopt,
                  const std::string& path = "t.txt") {
  CourseReadOptions o;
  o.dialect = dialect;
  return parse_course_scene(text, path, o);
}

std::string error_of(const std::string& text, const std::string& path = "t.txt",
                     std::optional<CourseDialect> dialect = std::nullopt) {
  try {
    parse(text, dialect, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

using test::where;

void write_file(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

void write_picture(const fs::path& p, int size = 2) { write_image(p.string(), Image(size, size, 3, 0.5f)); }

void write_cube_map(const fs::path& dir, const std::string& extension) {
  fs::create_directories(dir);
  for (const char* face : kFaces) write_picture(dir / (std::string(face) + extension));
}

// The centre pixel (of a 3x3 render: the ray along the camera's direction) in linear float.
vec3 centre_pixel(const Scene& scene, bool shadows = false, int bounces = 0) {
  PreparedScene p = prepare_scene(scene);
  RenderOptions o;
  o.width = o.height = 3;
  o.shadows = shadows;
  o.bounces = bounces;
  o.threads = 1;
  RenderResult r = render(p, o);
  const float* c = r.color.at(1, 1);
  return vec3(c[0], c[1], c[2]);
}

void expect_near(vec3 got, vec3 want, float tol, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << what << " [" << k << "]";
}

// ---------------------------------------------------------------- detection

TEST(CourseA5, DialectDetection) {
  auto dialect = [](const std::string& body) { return parse(kCamera + body + "Group { numObjects 0 }\n").dialect; };
  EXPECT_EQ(dialect(""), CourseDialect::v2012);
  EXPECT_EQ(dialect("Materials { numMaterials 1 Material { refractionIndex 1.5 } }\n"), CourseDialect::a5);
  EXPECT_EQ(dialect("Materials { numMaterials 1 Material { Noise { color 1 0 0 color 0 1 0 } } }\n"),
            CourseDialect::a5);
  EXPECT_EQ(dialect("# Noise and refractionIndex only in a comment\n"), CourseDialect::v2012);
  // refractionIndex and Noise mean a5 with falloff too (a5's point lights
  // have it: scene13_diamond); falloff alone means 2019.
  EXPECT_EQ(dialect("Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 falloff 1 } }\n"
                    "Materials { numMaterials 1 Material { refractionIndex 1.5 } }\n"),
            CourseDialect::a5);
  EXPECT_EQ(dialect("Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 falloff 1 } }\n"
                    "Materials { numMaterials 1 Material { Noise { color 1 0 0 color 0 1 0 } } }\n"),
            CourseDialect::a5);
  EXPECT_EQ(dialect("Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 falloff 1 } }\n"),
            CourseDialect::v2019);

  auto dir = test::temp_dir("a5_dialect");
  write_cube_map(dir / "bmpsky", ".bmp");
  write_cube_map(dir / "pngsky", ".png");
  const std::string path = (dir / "s.txt").string();
  const std::string falloff = "Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 falloff 1 } }\n";
  auto scene = [&](const std::string& body) { return kCamera + body + "Group { numObjects 0 }\n"; };
  // .bmp faces are a5's alone, with or without falloff.
  EXPECT_EQ(parse(scene("Background { cubeMap bmpsky }\n"), {}, path).dialect, CourseDialect::a5);
  EXPECT_EQ(parse(scene(falloff + "Background { cubeMap bmpsky }\n"), {}, path).dialect, CourseDialect::a5);
  // .png faces are 2019's (the 2019 scene06_bunny_1k: a cube map and no falloff).
  EXPECT_EQ(parse(scene("Background { cubeMap pngsky }\n"), {}, path).dialect, CourseDialect::v2019);
  // The explicit dialect always wins (and then reads its own file type).
  EXPECT_EQ(parse(scene("Materials { numMaterials 1 Material { refractionIndex 1.5 } }\n"), CourseDialect::v2012, path)
                .dialect,
            CourseDialect::v2012);
  const std::string bmp_message = error_of(scene("Background { cubeMap pngsky }\n"), path, CourseDialect::a5);
  EXPECT_NE(bmp_message.find("has no right.bmp"), std::string::npos) << bmp_message;
  fs::remove_all(dir);
}

TEST(CourseA5, DialectNameAndDefaultBounces) {
  EXPECT_EQ(course_dialect_name(CourseDialect::a5), "a5");
  EXPECT_EQ(course_dialect_name(CourseDialect::v2019), "2019");
  EXPECT_EQ(course_dialect_name(CourseDialect::v2012), "2012");
  EXPECT_EQ(default_render_options(SceneFormat::course_txt, CourseDialect::a5).bounces, 4);
  EXPECT_EQ(default_render_options(SceneFormat::course_txt, CourseDialect::v2012).bounces, 0);
  EXPECT_EQ(default_render_options(SceneFormat::course_txt, CourseDialect::v2019).bounces, 0);
}

// ---------------------------------------------------------------- reading

TEST(CourseA5, MaterialsLightsAndNoise) {
  const std::string text = kCamera +
                           "Lights { numLights 1 PointLight { position 0 0 5 color 1 1 1 falloff 0.5 } }\n"
                           "Materials { numMaterials 1 PhongMaterial { diffuseColor 0.2 0.3 0.4 specularColor 1 1 1 "
                           "shininess 50 refractionIndex 1.3\n"
                           "  Noise { color 0.1 0.2 0.3 color 0.3 0.4 0.5 octaves 4 frequency 2 amplitude 4 } } }\n"
                           "Group { numObjects 0 }\n";
  CourseScene a5 = parse(text, CourseDialect::a5);
  const Material& m = a5.scene.materials.at(0);
  EXPECT_FALSE(m.specular_highlight) << "a5: shininess is read and ignored";
  EXPECT_EQ(m.shininess, 50.f);
  EXPECT_FALSE(m.back_faces_cast_shadows);
  EXPECT_EQ(m.refraction_index, 1.3f);
  EXPECT_TRUE(m.noise.enabled);
  EXPECT_EQ(m.noise.color1, vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(m.noise.color2, vec3(0.3f, 0.4f, 0.5f));
  EXPECT_EQ(m.noise.octaves, 4);
  EXPECT_EQ(m.noise.frequency, 2.f);
  EXPECT_EQ(m.noise.amplitude, 4.f);
  EXPECT_EQ(a5.scene.lights.at(0).falloff, 0.5f);
  EXPECT_EQ(a5.scene.lights.at(0).attenuation_constant, 1.f) << "a5: 1 / (1 + falloff d^2)";

  CourseScene v2019 = parse(text, CourseDialect::v2019);
  EXPECT_TRUE(v2019.scene.materials.at(0).specular_highlight);
  EXPECT_TRUE(v2019.scene.materials.at(0).back_faces_cast_shadows);
  EXPECT_EQ(v2019.scene.lights.at(0).attenuation_constant, 0.f) << "2019: 1 / (falloff d^2)";
  EXPECT_EQ(parse(text, CourseDialect::v2012).scene.lights.at(0).falloff, 0.f) << "2012: no attenuation";
}

// An OBJ of a strip of n vertices (n >= 3) in the plane z = 0, wound so
// that every face normal is +z.
std::string strip_obj(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += "v " + std::to_string(i / 2) + " " + std::to_string(i % 2) + " 0\n";
  for (int i = 0; i + 2 < n; ++i)
    s += i % 2 == 0 ? "f " + std::to_string(i + 1) + " " + std::to_string(i + 3) + " " + std::to_string(i + 2) + "\n"
                    : "f " + std::to_string(i + 1) + " " + std::to_string(i + 2) + " " + std::to_string(i + 3) + "\n";
  return s;
}

TEST(CourseA5, MeshesOfAtMost120VerticesAreFlat) {
  auto dir = test::temp_dir("a5_flat");
  write_file(dir / "m120.obj", strip_obj(120));
  write_file(dir / "m121.obj", strip_obj(121));
  const std::string path = (dir / "s.txt").string();
  auto mesh = [&](const char* file, CourseDialect d) {
    CourseScene cs = parse(kCamera + "Group { numObjects 1 TriangleMesh { obj_file " + file + " } }\n", d, path);
    return cs.scene.meshes.at(0);
  };
  const Mesh flat = mesh("m120.obj", CourseDialect::a5);
  EXPECT_EQ(flat.positions.size(), 120u);
  EXPECT_TRUE(flat.normals.empty()) << "120 vertices: flat face normals";
  const Mesh smooth = mesh("m121.obj", CourseDialect::a5);
  ASSERT_EQ(smooth.normals.size(), 121u) << "121 vertices: vertex normals";
  for (vec3 n : smooth.normals) EXPECT_EQ(n, vec3(0, 0, 1));
  EXPECT_EQ(mesh("m120.obj", CourseDialect::v2012).normals.size(), 120u) << "2012 is always smooth";
  fs::remove_all(dir);
}

TEST(CourseA5, BmpCubeMapFacesInTheCourseOrder) {
  auto dir = test::temp_dir("a5_cube");
  write_cube_map(dir / "sky", ".bmp");
  CourseScene cs =
      parse(kCamera + "Background { cubeMap sky }\nGroup { numObjects 0 }\n", {}, (dir / "s.txt").string());
  ASSERT_EQ(cs.dialect, CourseDialect::a5);
  for (int i = 0; i < 6; ++i) {
    ASSERT_NE(cs.scene.background.cube_map[size_t(i)], invalid);
    const Texture& t = cs.scene.textures.at(size_t(cs.scene.background.cube_map[size_t(i)]));
    EXPECT_EQ(fs::path(t.path).filename().string(), std::string(kFaces[i]) + ".bmp");
    EXPECT_EQ(t.lookup, Texture::Lookup::course) << "bilinear as the textures";
  }
  // Decoded through the project's BMP reader, and shown where rays miss.
  EXPECT_NEAR(centre_pixel(cs.scene).x, 127.f / 255.f, 1e-6f);  // 0.5 written as 8 bits
  fs::remove_all(dir);
}

TEST(CourseA5, WrittenBackAsA5) {
  // The course writer picks a5 for a5 materials and writes Noise, falloff and
  // .bmp cube map faces; reading that back gives the same scene data, as does
  // a .glb (rayform's extras).
  auto dir = test::temp_dir("a5_write");
  write_cube_map(dir / "sky", ".bmp");
  const std::string text = kCamera +
                           "Lights { numLights 1 PointLight { position 0 0 5 color 1 1 1 falloff 0.5 } }\n"
                           "Background { cubeMap sky }\n"
                           "Materials { numMaterials 1 Material { diffuseColor 0.2 0.3 0.4 specularColor 1 1 1 "
                           "refractionIndex 1.3\n"
                           "  Noise { color 0.1 0.2 0.3 color 0.3 0.4 0.5 octaves 4 frequency 2 amplitude 4 } } }\n"
                           "Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }\n";
  const Scene a = parse(text, {}, (dir / "s.txt").string()).scene;
  fs::create_directories(dir / "out");
  save_scene(a, (dir / "out" / "w.txt").string());
  const LoadedScene b = load_scene((dir / "out" / "w.txt").string());
  EXPECT_EQ(b.dialect, CourseDialect::a5);
  const Material &ma = a.materials.at(0), &mb = b.scene.materials.at(0);
  EXPECT_EQ(mb.refraction_index, ma.refraction_index);
  EXPECT_EQ(mb.specular_highlight, false);
  EXPECT_EQ(mb.noise.enabled, true);
  EXPECT_EQ(mb.noise.color1, ma.noise.color1);
  EXPECT_EQ(mb.noise.color2, ma.noise.color2);
  EXPECT_EQ(mb.noise.octaves, 4);
  EXPECT_EQ(mb.noise.frequency, 2.f);
  EXPECT_EQ(mb.noise.amplitude, 4.f);
  EXPECT_EQ(b.scene.lights.at(0).falloff, 0.5f);
  EXPECT_EQ(b.scene.lights.at(0).attenuation_constant, 1.f);
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(fs::path(b.scene.textures.at(size_t(b.scene.background.cube_map[size_t(i)])).path).extension(), ".bmp");
  // Through glTF: the a5 material and light data in rayform's extras.
  save_scene(a, (dir / "out" / "w.glb").string());
  const Scene g = load_scene((dir / "out" / "w.glb").string()).scene;
  const Material& mg = g.materials.at(0);
  EXPECT_FALSE(mg.specular_highlight);
  EXPECT_FALSE(mg.back_faces_cast_shadows);
  EXPECT_TRUE(mg.noise.enabled);
  EXPECT_EQ(mg.noise.color1, ma.noise.color1);
  EXPECT_EQ(mg.noise.color2, ma.noise.color2);
  EXPECT_EQ(mg.noise.octaves, 4);
  EXPECT_EQ(mg.noise.frequency, 2.f);
  EXPECT_EQ(mg.noise.amplitude, 4.f);
  EXPECT_EQ(g.lights.at(0).falloff, 0.5f);
  EXPECT_EQ(g.lights.at(0).attenuation_constant, 1.f);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------- errors

TEST(CourseA5Errors, RefractionIndex) {
  const std::string neg = kCamera + "Materials { numMaterials 1\n  Material { refractionIndex -1.5 } }\n";
  const std::string m = error_of(neg);
  EXPECT_EQ(m.rfind(where(neg, "-1.5") + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("refractionIndex must be 0 (opaque) or positive"), std::string::npos) << m;
  const std::string nan = kCamera + "Materials { numMaterials 1\n  Material { refractionIndex nan } }\n";
  EXPECT_EQ(error_of(nan).rfind(where(nan, "nan }") + ": expected a finite number", 0), 0u) << error_of(nan);
  EXPECT_EQ(error_of(kCamera + "Materials { numMaterials 1 Material { refractionIndex 0 } }\n"), "")
      << "0 means opaque";
}

TEST(CourseA5Errors, Noise) {
  const std::string neg =
      kCamera + "Materials { numMaterials 1 Material {\n  Noise { color 1 0 0 color 0 1 0 octaves -2 } } }\n";
  std::string m = error_of(neg);
  EXPECT_EQ(m.rfind(where(neg, "-2") + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("octaves must be a whole number from 0 to"), std::string::npos) << m;
  const std::string half =
      kCamera + "Materials { numMaterials 1 Material {\n  Noise { color 1 0 0 color 0 1 0 octaves 2.5 } } }\n";
  EXPECT_EQ(error_of(half).rfind(where(half, "2.5") + ": ", 0), 0u) << error_of(half);
  const std::string one = kCamera + "Materials { numMaterials 1 Material {\n  Noise { color 1 0 0 octaves 2 } } }\n";
  m = error_of(one);
  EXPECT_EQ(m.rfind(where(one, "Noise") + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("Noise needs two colours"), std::string::npos) << m;
  const std::string three =
      kCamera + "Materials { numMaterials 1 Material {\n  Noise { color 1 0 0 color 0 1 0 color 0 0 1 } } }\n";
  EXPECT_EQ(error_of(three).rfind(where(three, "color 0 0 1") + ": ", 0), 0u) << error_of(three);
  const std::string unknown = kCamera + "Materials { numMaterials 1 Material {\n  Noise { colour 1 0 0 } } }\n";
  m = error_of(unknown);
  EXPECT_EQ(m.rfind(where(unknown, "colour") + ": expected one of color, octaves", 0), 0u) << m;
}

TEST(CourseA5Errors, CubeMapFaces) {
  auto dir = test::temp_dir("a5_cube_errors");
  const std::string path = (dir / "s.txt").string();
  write_cube_map(dir / "sky", ".bmp");
  fs::remove(dir / "sky" / "up.bmp");
  const std::string text = kCamera + "Background {\n  cubeMap sky }\nGroup { numObjects 0 }\n";
  std::string m = error_of(text, path);
  EXPECT_EQ(m.rfind(where(text, "sky }", 1, path) + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("cube map folder has no up.bmp"), std::string::npos) << m;
  // A face of another size: refused when the faces are decoded, naming both files.
  write_picture(dir / "sky" / "up.bmp", 4);
  CourseScene cs = parse(text, {}, path);
  try {
    prepare_scene(cs.scene);
    ADD_FAILURE() << "a face of another size was accepted";
  } catch (const Error& e) {
    m = e.what();
    EXPECT_NE(m.find("up.bmp (4x4): cube map face of another size than"), std::string::npos) << m;
    EXPECT_NE(m.find("right.bmp (2x2)"), std::string::npos) << m;
  }
  fs::remove_all(dir);
}

// ---------------------------------------------------------------- shading

// A unit sphere at the origin seen head-on, lit along the view axis: the
// centre ray hits (0, 0, 1) with N = L = R = (0, 0, 1).
const std::string kHeadOnSphere = kCamera +
                                  "Lights { numLights 1 DirectionalLight { direction 0 0 -1 color 1 1 1 } }\n"
                                  "Materials { numMaterials 1 Material { diffuseColor 0.5 0.5 0.5 "
                                  "specularColor 1 1 1 shininess 10 } }\n"
                                  "Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }\n";

TEST(CourseA5Render, NoHighlight) {
  expect_near(centre_pixel(parse(kHeadOnSphere, CourseDialect::a5).scene), vec3(0.5f), 1e-6f, "a5: diffuse only");
  expect_near(centre_pixel(parse(kHeadOnSphere, CourseDialect::v2012).scene), vec3(1.5f), 1e-5f,
              "2012: diffuse + (L.R)^10");
}

TEST(CourseA5Render, PointLightAttenuation) {
  // The centre ray hits (0, 0, 1), 4 from the light: d^2 = 16.
  const std::string text = kCamera +
                           "Lights { numLights 1 PointLight { position 0 0 5 color 1 1 1 falloff 0.5 } }\n"
                           "Group { numObjects 1 Sphere { center 0 0 0 radius 1 } }\n";
  expect_near(centre_pixel(parse(text, CourseDialect::a5).scene), vec3(1.f / 9.f), 1e-6f, "a5: 1 / (1 + 0.5 * 16)");
  expect_near(centre_pixel(parse(text, CourseDialect::v2019).scene), vec3(1.f / 8.f), 1e-6f, "2019: 1 / (0.5 * 16)");
}

TEST(CourseA5Render, NoiseReplacesTheDiffuseColourInTheDiffuseTermOnly) {
  // The plane z = 0 facing the camera, lit head-on; the centre ray hits the
  // origin, a lattice point where every octave of the noise is 0: M = 0, w = 1/2.
  const std::string text = kCamera +
                           "Lights { numLights 1 DirectionalLight { direction 0 0 -1 color 1 1 1 } }\n"
                           "Background { ambientLight 0.25 0.25 0.25 }\n"
                           "Materials { numMaterials 1 Material { diffuseColor 1 0 0\n"
                           "  Noise { color 0.2 0.4 0.6 color 0.6 0.2 0 octaves 3 frequency 2 amplitude 4 } } }\n"
                           "Group { numObjects 1 MaterialIndex 0 Plane { normal 0 0 1 offset 0 } }\n";
  const Scene scene = parse(text).scene;
  const vec3 half = 0.5f * vec3(0.2f, 0.4f, 0.6f) + 0.5f * vec3(0.6f, 0.2f, 0.f);
  expect_near(centre_pixel(scene), 0.25f * vec3(1, 0, 0) + half, 1e-6f, "ambient on diffuseColor, diffuse on noise");
  // The left-middle pixel: x = -1, the point (-10 tan 15deg, 0, 0).
  PreparedScene p = prepare_scene(scene);
  RenderOptions o;
  o.width = o.height = 3;
  RenderResult r = render(p, o);
  const float x = -10.f * float(std::tan(15.0 * 3.14159265358979323846 / 180.0));
  const float w = course_noise_weight(vec3(x, 0, 0), 3, 2.f, 4.f);
  ASSERT_GT(std::abs(w - 0.5f), 0.05f) << "a point where the noise is not 1/2";
  const vec3 want = 0.25f * vec3(1, 0, 0) + w * vec3(0.2f, 0.4f, 0.6f) + (1 - w) * vec3(0.6f, 0.2f, 0.f);
  expect_near(vec3(r.color.at(0, 1)[0], r.color.at(0, 1)[1], r.color.at(0, 1)[2]), want, 1e-4f,
              "noise off the lattice");
}

TEST(CourseA5Render, ShadowsFallOnlyFromSurfacesFacingThePoint) {
  // The plane z = 0 lit by a directional light towards (1, 0, 1)/sqrt 2; a
  // triangle in the plane x + z = 4 crosses the shadow ray of the origin
  // (not the camera's ray). Wound with its normal towards the light, it is
  // seen from behind by the origin: lit in a5, shadowed in 2012.
  auto scene = [](const char* v1, const char* v2) {
    return kCamera + "Lights { numLights 1 DirectionalLight { direction -1 0 -1 color 1 1 1 } }\n" +
           "Group { numObjects 2 Plane { normal 0 0 1 offset 0 }\n" + "  Triangle { vertex0 1 -2 3 vertex1 " + v1 +
           " vertex2 " + v2 + " } }\n";
  };
  const std::string away = scene("3 -2 1", "2 3 2"), facing = scene("2 3 2", "3 -2 1");
  const float lit = float(1.0 / std::sqrt(2.0));
  expect_near(centre_pixel(parse(away, CourseDialect::a5).scene, true), vec3(lit), 1e-6f, "a5, back face: lit");
  expect_near(centre_pixel(parse(facing, CourseDialect::a5).scene, true), vec3(0.f), 0.f, "a5, front face: shadow");
  expect_near(centre_pixel(parse(away, CourseDialect::v2012).scene, true), vec3(0.f), 0.f, "2012: any surface");
  expect_near(centre_pixel(parse(away, CourseDialect::a5).scene, false), vec3(lit), 1e-6f, "without -shadows");
  // Shapes before any MaterialIndex get a default material with a5's rules.
  const Scene a5 = parse(away, CourseDialect::a5).scene;
  ASSERT_EQ(a5.materials.size(), 1u);
  EXPECT_FALSE(a5.materials[0].back_faces_cast_shadows);
  EXPECT_TRUE(parse(away, CourseDialect::v2012).scene.materials.empty()) << "2012 keeps the renderer's default";
}

TEST(CourseA5Render, ReflectionWeightedByTheSpecularColour) {
  // A mirror (refractionIndex 0) sphere head-on, no light: the centre ray
  // reflects straight back to the background (a grey 0.5): ks * 0.5.
  const std::string text = kCamera + "Background { color 0.5 0.5 0.5 }\nLights { numLights 0 }\n" +
                           "Materials { numMaterials 1 Material { diffuseColor 0 0 0 specularColor 0.5 0.25 1 "
                           "refractionIndex 0 } }\n"
                           "Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }\n";
  Scene s = parse(text, CourseDialect::a5).scene;
  s.background.ambient = vec3(0.f);  // numLights 0 makes it white; the diffuse colour is black anyway
  expect_near(centre_pixel(s, false, 1), vec3(0.25f, 0.125f, 0.5f), 1e-6f, "one bounce");
  expect_near(centre_pixel(s, false, 0), vec3(0.f), 0.f, "no bounce");
}

}  // namespace
}  // namespace rayform
