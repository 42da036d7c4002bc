// Hostile files refused before they cost memory, time or secrets: the limits
// (base/limits.h) checked by the readers and load_scene, glTF node graphs
// that are not trees, JSON nested too deep, files that never end (devices),
// and --confine (referenced_files.h) for every kind of file a scene names.
// All inputs are written here.
#include "rayform/importers/gltf/gltf_reader.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/referenced_files.h"
#include "rayform/base/error.h"
#include "rayform/importers/scene_io.h"
#include "rayform/importers/scene_writer.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace rayform {
namespace {
namespace fs = std::filesystem;

// One triangle (0,0,0), (1,0,0), (0,1,0) as nine little-endian floats.
constexpr const char* triangle_base64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

void put(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A glTF with `nodes_json` as its nodes, scene 0 listing `roots_json`, one
// mesh of one triangle whose POSITION comes from `buffer_uri` (36 bytes).
std::string gltf(const std::string& nodes_json, const std::string& roots_json = "[0]",
                 const std::string& buffer_uri = std::string("data:application/octet-stream;base64,") + triangle_base64,
                 const std::string& extra = "") {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)" + roots_json + R"(}],"nodes":)" + nodes_json +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"buffers":[{"byteLength":36,"uri":")" +
         buffer_uri + "\"}]" + extra + "}";
}

// The message of the Error `f` throws ("" when it does not throw).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(HostileGltf, NodeWithTwoParentsIsRefusedAtOnce) {
  // 40 levels of two nodes, each naming both nodes below: 2^40 paths.
  std::string nodes = "[";
  for (int level = 0; level < 40; ++level)
    for (int k = 0; k < 2; ++k) {
      nodes += level ? "," : (k ? "," : "");
      nodes += level + 1 < 40
                   ? R"({"children":[)" + std::to_string(2 * level + 2) + "," + std::to_string(2 * level + 3) + "]}"
                   : std::string(R"({"mesh":0})");
    }
  nodes += "]";
  const fs::path dir = test::temp_dir("hostile_dag");
  put(dir / "dag.gltf", gltf(nodes));
  const std::string e = error_of([&] { read_gltf_scene((dir / "dag.gltf").string()); });
  EXPECT_NE(e.find("dag.gltf: nodes[2]: has two parents, nodes[0] and nodes[1]"), std::string::npos) << e;
}

TEST(HostileGltf, SceneListingAChildOrANodeTwiceIsRefused) {
  const fs::path dir = test::temp_dir("hostile_roots");
  put(dir / "child.gltf", gltf(R"([{"children":[1]},{"mesh":0}])", "[0,1]"));
  EXPECT_NE(error_of([&] {
              read_gltf_scene((dir / "child.gltf").string());
            }).find("scenes[0].nodes[1]: nodes[1] is a child of nodes[0]"),
            std::string::npos);
  put(dir / "twice.gltf", gltf(R"([{"mesh":0}])", "[0,0]"));
  EXPECT_NE(error_of([&] { read_gltf_scene((dir / "twice.gltf").string()); }).find("nodes[0] is listed twice"),
            std::string::npos);
  put(dir / "tree.gltf", gltf(R"([{"children":[1,2]},{"mesh":0},{"mesh":0}])"));
  EXPECT_EQ(error_of([&] { read_gltf_scene((dir / "tree.gltf").string()); }), "");
}

TEST(HostileGltf, JsonNestedDeeperThanTheLimitIsRefusedWithItsPlace) {
  const fs::path dir = test::temp_dir("hostile_json");
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  put(dir / "deep.gltf",
      gltf(R"([{"mesh":0}])", "[0]", std::string("data:application/octet-stream;base64,") + triangle_base64,
           ",\"extras\":" + deep));
  const std::string e = error_of([&] { read_gltf_scene((dir / "deep.gltf").string()); });
  EXPECT_NE(e.find("deep.gltf: line 4, column 645: "), std::string::npos) << e;  // the 512th [ is level 513
  EXPECT_NE(e.find("nest more than 512 levels"), std::string::npos) << e;
  // Brackets inside strings do not count; a raised limit admits the file.
  put(dir / "strings.gltf", gltf(R"([{"mesh":0,"name":")" + std::string(1000, '[') + R"("}])"));
  EXPECT_EQ(error_of([&] { read_gltf_scene((dir / "strings.gltf").string()); }), "");
  const std::string thousand = std::string(1000, '[') + std::string(1000, ']');
  put(dir / "thousand.gltf",
      gltf(R"([{"mesh":0}])", "[0]", std::string("data:application/octet-stream;base64,") + triangle_base64,
           ",\"extras\":" + thousand));
  EXPECT_NE(error_of([&] { read_gltf_scene((dir / "thousand.gltf").string()); }), "");
  GltfReadOptions raised;
  raised.limits.json_depth = max_json_depth;
  EXPECT_EQ(error_of([&] { read_gltf_scene((dir / "thousand.gltf").string(), raised); }), "");
}

TEST(HostileGltf, AccessorsWithoutDataAreBoundedByTheUnbackedLimit) {
  const fs::path dir = test::temp_dir("hostile_accessor");
  auto file = [&](int count) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"accessors":[{"componentType":5126,"count":)" +
           std::to_string(count) + R"(,"type":"VEC3","min":[0,0,0],"max":[0,0,0]}]})";
  };
  GltfReadOptions small;
  small.limits.unbacked_elements = 6;
  put(dir / "seven.gltf", file(7));
  put(dir / "six.gltf", file(6));
  ASSERT_NE(error_of([&] {
              read_gltf_scene((dir / "seven.gltf").string(), small);
            }).find("(accessors[0]): count 7 without a bufferView: unbacked-elements: 7 is more than the limit of 6"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { read_gltf_scene((dir / "six.gltf").string(), small); }), "");
  // Just under the vertex limit (a 700-byte file that rendered 134 million
  // zero vertices): refused by the default limit before anything is allocated.
  put(dir / "bomb.gltf", file(134217723));
  const std::string e = error_of([&] { read_gltf_scene((dir / "bomb.gltf").string()); });
  EXPECT_NE(e.find("bomb.gltf: meshes[0].primitives[0].attributes.POSITION (accessors[0]): count 134217723 without a "
                   "bufferView: unbacked-elements: 134217723 is more than the limit of 16777216 (raise it with --limit "
                   "unbacked-elements=N)"),
            std::string::npos)
      << e;
}

// A mesh of `count` vertices without data and one morph target (without
// data) on `nodes` nodes, node k with weight (k + 1) / nodes: a mesh copy each.
std::string morphed_nodes(int count, int nodes) {
  std::string node_list, roots;
  for (int k = 0; k < nodes; ++k) {
    node_list +=
        (k ? "," : "") + std::string(R"({"mesh":0,"weights":[)") + std::to_string(double(k + 1) / nodes) + "]}";
    roots += (k ? "," : "") + std::to_string(k);
  }
  const std::string n = std::to_string(count);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + roots + R"(]}],"nodes":[)" + node_list +
         R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}]}],
"accessors":[{"componentType":5126,"count":)" +
         n + R"(,"type":"VEC3","min":[0,0,0],"max":[0,0,0]},{"componentType":5126,"count":)" + n +
         R"(,"type":"VEC3","min":[0,0,0],"max":[0,0,0]}]})";
}

TEST(HostileGltf, MeshCopiesPerMorphWeightsCountAgainstTheLimitsBeforeTheyAreBuilt) {
  const fs::path dir = test::temp_dir("hostile_morph");
  // Each copy reads both accessors again: 4 copies of 2 x 30 elements.
  put(dir / "four.gltf", morphed_nodes(30, 4));
  GltfReadOptions o;
  o.limits.unbacked_elements = 200;
  ASSERT_NE(error_of([&] { read_gltf_scene((dir / "four.gltf").string(), o); })
                .find("four.gltf: meshes[0].primitives[0].attributes.POSITION (accessors[0]): count 30 without a "
                      "bufferView (after 180 read before): unbacked-elements: 210 is more than the limit of 200"),
            std::string::npos)
      << error_of([&] { read_gltf_scene((dir / "four.gltf").string(), o); });
  o.limits.unbacked_elements = 240;
  EXPECT_EQ(error_of([&] { read_gltf_scene((dir / "four.gltf").string(), o); }), "");
  // Vertices and triangles of every copy, before it is built.
  o.limits.vertices = 119;
  EXPECT_NE(error_of([&] { read_gltf_scene((dir / "four.gltf").string(), o); })
                .find("four.gltf: meshes[0], with the meshes built before it: vertices: 120 is more than the limit of "
                      "119 (raise it with --limit vertices=N)"),
            std::string::npos);
  o.limits.vertices = 120;
  o.limits.triangles = 39;
  EXPECT_NE(error_of([&] {
              read_gltf_scene((dir / "four.gltf").string(), o);
            }).find("triangles: 40 is more than the limit of 39"),
            std::string::npos);
  // The issue's file: 64 nodes, 2^21 vertices each (2.15 GB once built).
  put(dir / "sixtyfour.gltf", morphed_nodes(1 << 21, 64));
  EXPECT_NE(error_of([&] {
              read_gltf_scene((dir / "sixtyfour.gltf").string());
            }).find("unbacked-elements: 18874368 is more than the limit of 16777216"),
            std::string::npos);
}

TEST(HostileGltf, InstancesCountAgainstTheLimitBeforeTheirMatricesAreBuilt) {
  const fs::path dir = test::temp_dir("hostile_instances");
  auto file = [](int count) {
    std::string f = gltf(R"([{"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1}}}}])",
                         "[0]", std::string("data:application/octet-stream;base64,") + triangle_base64,
                         R"(,"extensionsUsed":["EXT_mesh_gpu_instancing"])");
    const std::string first = R"("max":[1,1,0]})";
    f.insert(f.find(first) + first.size(),
             R"(,{"componentType":5126,"count":)" + std::to_string(count) + R"(,"type":"VEC3"})");
    return f;
  };
  put(dir / "thousand.gltf", file(1000));
  put(dir / "more.gltf", file(1001));
  GltfReadOptions o;
  o.limits.instances = 1000;
  ASSERT_NE(error_of([&] { read_gltf_scene((dir / "more.gltf").string(), o); })
                .find("more.gltf: nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.TRANSLATION: 1001 instances: "
                      "instances: 1001 is more than the limit of 1000 (raise it with --limit instances=N)"),
            std::string::npos)
      << error_of([&] { read_gltf_scene((dir / "more.gltf").string(), o); });
  EXPECT_EQ(error_of([&] { read_gltf_scene((dir / "thousand.gltf").string(), o); }), "");
  // The issue's file: 2^25 instances without data, refused before any is built.
  put(dir / "many.gltf", file(1 << 25));
  EXPECT_NE(error_of([&] {
              read_gltf_scene((dir / "many.gltf").string(), o);
            }).find("TRANSLATION: 33554432 instances: instances: 33554432 is more than the limit of 1000"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read_gltf_scene((dir / "many.gltf").string());
            }).find("TRANSLATION (accessors[1]): count 33554432 without a bufferView: unbacked-elements"),
            std::string::npos);
}

// The peak resident memory of this process since reset_peak_memory(), in
// kilobytes (Linux: /proc/self/status VmHWM; 0 where it cannot be read).
size_t peak_memory_kb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmHWM:", 0) == 0) return size_t(std::stoull(line.substr(6)));
  return 0;
}
void reset_peak_memory() { std::ofstream("/proc/self/clear_refs") << "5"; }

TEST(HostileObj, TextWithoutLineEndsOrFacesFailsAtOnceWithoutBecomingResident) {
  const fs::path dir = test::temp_dir("hostile_obj");
  // The error of reading `head` followed by zeros up to `bytes` (a sparse
  // file: no disk used).
  auto error_with_zeros = [&](const std::string& name, const std::string& head, size_t bytes) {
    const fs::path file = dir / name;
    std::ofstream(file, std::ios::binary) << head;
    fs::resize_file(file, bytes);
    const std::string error = error_of([&] { read_obj_scene(file.string()); });
    fs::remove(file);
    return error;
  };
  const std::string too_long = ": line longer than 67108864 bytes (not an OBJ text)";
  // 200 MB of zeros without a line end.
  reset_peak_memory();
  const size_t before = peak_memory_kb();
  EXPECT_EQ(error_with_zeros("zeros.obj", std::string(1, '\0'), size_t(200) << 20),
            (dir / "zeros.obj").string() + ":1" + too_long);
  if (before > 0) {
    EXPECT_LT(peak_memory_kb(), before + 100 * 1024);  // at most 64 MB read
  }
  // The same after three lines, ended by "\r\n", a lone '\r' and '\n': line 4.
  EXPECT_EQ(error_with_zeros("late.obj", "v 0 0 0\r\nv 1 0 0\rv 0 1 0\n", size_t(100) << 20),
            (dir / "late.obj").string() + ":4" + too_long);
  // A line that only starts with 'f' after a '\n' is not a face line: the walk goes on to line 3.
  EXPECT_EQ(error_with_zeros("not_face.obj", "v 0 0 0\nfoo 1 2 3\n", size_t(100) << 20),
            (dir / "not_face.obj").string() + ":3" + too_long);
  // 200 MB of lines without a face: read once, let go behind the walk.
  const fs::path lines = dir / "lines.obj";
  {
    std::ofstream out(lines, std::ios::binary);
    const std::string block = "# " + std::string(1000, 'x') + "\nv 0 0 0\n";
    for (size_t written = 0; written < (size_t(200) << 20); written += block.size()) out << block;
  }
  reset_peak_memory();
  const size_t before_lines = peak_memory_kb();
  EXPECT_EQ(error_of([&] { read_obj_scene(lines.string()); }), lines.string() + ": OBJ file has no faces");
  if (before_lines > 0) {
    EXPECT_LT(peak_memory_kb(), before_lines + 150 * 1024);
  }
  fs::remove(lines);
  // A face anywhere, and lines ending in '\r' alone, are fine.
  put(dir / "cr.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r");
  EXPECT_EQ(error_of([&] { read_obj_scene((dir / "cr.obj").string()); }), "");
}

TEST(HostileScenes, TotalsAboveTheLimitsAreRefusedByLoadScene) {
  const fs::path dir = test::temp_dir("hostile_totals");
  put(dir / "two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  LoadOptions o;
  o.limits.triangles = 1;
  EXPECT_NE(error_of([&] {
              load_scene((dir / "two.obj").string(), o);
            }).find("two.obj: triangles: 2 is more than the limit of 1 (raise it with --limit triangles=N)"),
            std::string::npos);
  o.limits.triangles = 2;
  o.limits.vertices = 3;
  EXPECT_NE(error_of([&] { load_scene((dir / "two.obj").string(), o); }).find("vertices: 4 is more than"),
            std::string::npos);
  o.limits.vertices = 4;
  EXPECT_EQ(error_of([&] { load_scene((dir / "two.obj").string(), o); }), "");
}

// A course scene whose one mesh (and, if given, texture) are the names given.
std::string course_scene(const std::string& mesh, const std::string& texture = "") {
  return "PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }\n"
         "Lights { numLights 0 }\nBackground { color 0 0 0 }\n"
         "Materials { numMaterials 1 Material { diffuseColor 1 1 1 " +
         (texture.empty() ? std::string() : "texture " + texture) +
         " } }\n"
         "Group { numObjects 1 MaterialIndex 0 TriangleMesh { obj_file " +
         mesh + " } }\n";
}

TEST(HostileScenes, DevicesAreNotReadEvenWithoutConfine) {
  const fs::path dir = test::temp_dir("hostile_device");
  put(dir / "zero.txt", course_scene("/dev/zero"));
  EXPECT_NE(error_of([&] {
              load_scene((dir / "zero.txt").string());
            }).find("zero.txt:5:62: mesh file '/dev/zero' (/dev/zero) is not a regular file"),
            std::string::npos)
      << error_of([&] { load_scene((dir / "zero.txt").string()); });
}

// Found by the fuzzer: a name longer than the system's limit (ENAMETOOLONG)
// made std::filesystem throw past the readers' errors.
TEST(HostileScenes, NameTooLongForTheSystemIsNotFoundWithItsPlace) {
  const fs::path dir = test::temp_dir("hostile_long_name");
  const std::string name = "mesh" + std::string(5000, 'x') + ".obj";
  put(dir / "long.txt", course_scene(name));
  const std::string message = error_of([&] { load_scene((dir / "long.txt").string()); });
  EXPECT_NE(message.find("long.txt:5:62: cannot find mesh file 'mesh" + std::string(60, 'x') + "...' (looked beside"),
            std::string::npos)
      << message;
  EXPECT_LT(message.size(), 400u);
}

TEST(Confine, RefusesEveryWayOutAndAdmitsTheFolder) {
  const fs::path root = test::temp_dir("confine");
  const fs::path in = root / "in", out = root / "outside";
  put(out / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  put(out / "x.mtl", "newmtl m\nKd 1 0 0\nmap_Kd tex.png\n");
  put(in / "sub" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  fs::create_symlink(out / "tri.obj", in / "link.obj");
  LoadOptions confined;
  confined.access.confine = true;
  auto problem = [&](const std::string& file, const std::string& text, const LoadOptions& o) {
    put(in / file, text);
    return error_of([&] { load_scene((in / file).string(), o); });
  };
  // Course: '..', absolute, a symlink leading out; a subfolder is fine.
  EXPECT_NE(problem("up.txt", course_scene("../outside/tri.obj"), confined)
                .find("mesh file '../outside/tri.obj' lies outside the scene's folder"),
            std::string::npos);
  EXPECT_NE(problem("abs.txt", course_scene((out / "tri.obj").string()), confined).find("is an absolute path"),
            std::string::npos);
  EXPECT_NE(problem("link.txt", course_scene("link.obj"), confined).find("'link.obj' lies outside"), std::string::npos);
  EXPECT_EQ(problem("sub.txt", course_scene("sub/tri.obj"), confined), "");
  // Without --confine the same files are read.
  EXPECT_EQ(problem("up.txt", course_scene("../outside/tri.obj"), LoadOptions{}), "");
  EXPECT_EQ(problem("link.txt", course_scene("link.obj"), LoadOptions{}), "");
  // OBJ: an mtllib leading out.
  EXPECT_NE(problem("m.obj", "mtllib ../outside/x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", confined)
                .find("m.obj:1: mtllib '../outside/x.mtl' lies outside"),
            std::string::npos);
  // glTF: a buffer leading out, a URI with a scheme; data: URIs are fine.
  EXPECT_NE(problem("b.gltf", gltf(R"([{"mesh":0}])", "[0]", "../outside/tri.obj"), confined)
                .find("b.gltf: uri '../outside/tri.obj' lies outside"),
            std::string::npos);
  EXPECT_NE(problem("h.gltf", gltf(R"([{"mesh":0}])", "[0]", "http://example.com/a.bin"), confined)
                .find("uri 'http://example.com/a.bin' is a URI; only data: URIs are read under --confine"),
            std::string::npos);
  EXPECT_EQ(problem("d.gltf", gltf(R"([{"mesh":0}])"), confined), "");
}

TEST(HostileScenes, ConvertNeverReplacesAnInput) {
  // The writer names the mesh read from teapot.obj "o_teapot.obj" for the
  // output o.txt: the scene's other mesh file.
  const fs::path dir = test::temp_dir("hostile_convert");
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  put(dir / "teapot.obj", tri);
  put(dir / "o_teapot.obj", tri + "# the input\n");
  put(dir / "s.txt",
      "PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }\n"
      "Materials { numMaterials 1 Material { diffuseColor 1 1 1 } }\n"
      "Group { numObjects 2 MaterialIndex 0 Transform { Translate 1 0 0 TriangleMesh { obj_file teapot.obj } }\n"
      "  TriangleMesh { obj_file o_teapot.obj } }\n");
  const LoadedScene loaded = load_scene((dir / "s.txt").string());
  const std::string e = error_of([&] { save_scene(loaded.scene, (dir / "o.txt").string()); });
  EXPECT_NE(e.find("o_teapot.obj: writing it would replace"), std::string::npos) << e;
  std::ifstream in(dir / "o_teapot.obj");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), tri + "# the input\n");
  EXPECT_FALSE(fs::exists(dir / "o.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);  // nothing else written
}

TEST(HostileScenes, WritersKeepEveryFileInTheOutputsFolder) {
  // Names from a hostile input: a mesh and a texture whose names lead out.
  Scene s;
  s.cameras.push_back(Camera{});
  Texture t;
  t.name = "../../../evil/tex";
  t.width = t.height = 2;
  t.channels = 3;
  t.pixels.assign(12, 200);
  s.textures.push_back(t);
  Material m;
  m.name = "../m";
  m.diffuse_texture = 0;
  s.materials.push_back(m);
  Mesh mesh;
  mesh.name = "/etc/../../up/mesh";
  mesh.positions = {vec3(0.f), vec3(1.f, 0.f, 0.f), vec3(0.f, 1.f, 0.f)};
  mesh.uvs = {vec2(0.f), vec2(1.f, 0.f), vec2(0.f, 1.f)};
  mesh.indices = {0, 1, 2};
  s.meshes.push_back(mesh);
  Node shape;
  shape.kind = Node::Kind::shape;
  shape.name = "../../node";
  shape.shape_kind = ShapeKind::mesh;
  shape.shape = 0;
  shape.material = 0;
  s.nodes.push_back(shape);
  Node root;
  root.children = {0};
  s.nodes.push_back(root);
  s.root = 1;
  const fs::path dir = test::temp_dir("hostile_names");
  const fs::path out = dir / "deep" / "out";
  fs::create_directories(out);
  for (const char* name : {"o.txt", "o.obj", "o.gltf", "o.glb"}) {
    const SaveResult r = save_scene(s, (out / name).string());
    EXPECT_FALSE(r.files.empty()) << name;
    for (const std::string& f : r.files) EXPECT_TRUE(lies_within_folder(f, out)) << name << " wrote " << f;
  }
  // Nothing appeared anywhere but in out/.
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      EXPECT_TRUE(lies_within_folder(e.path(), out)) << e.path();
    }
}

TEST(Confine, UriSchemes) {
  EXPECT_TRUE(has_uri_scheme("http://x"));
  EXPECT_TRUE(has_uri_scheme("file:///etc/passwd"));
  EXPECT_TRUE(has_uri_scheme("data:application/octet-stream;base64,AA=="));
  EXPECT_FALSE(has_uri_scheme("C:/textures/a.png"));  // a drive letter
  EXPECT_FALSE(has_uri_scheme("textures/a:b.png"));
  EXPECT_FALSE(has_uri_scheme("a.png"));
}

}  // namespace
}  // namespace rayform
