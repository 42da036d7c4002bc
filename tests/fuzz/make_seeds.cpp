// Writes the fuzz targets' seed corpora into OUT/<target>/ (scripts/fuzz runs
// it into the fuzz build folder; nothing it writes is committed):
//   rayform_fuzz_seeds SOURCE_DIR OUT [SHARED_DIR]
// - our own scenes (SOURCE_DIR/scenes) as course bundles, as OBJ bundles, and
//   converted by rayform's writers to .gltf (embedded) and .glb;
// - generated meshes (procedural_mesh.h) as OBJ and as glTF files that use
//   EXT_meshopt_compression (KHR_draco_mesh_compression: make_draco_seeds.cpp),
//   KHR_mesh_quantization, sparse accessors, EXT_mesh_gpu_instancing and an
//   embedded PNG with KHR_texture_transform; morph weights per node and
//   accessors without a bufferView (count_seeds);
// - small images written by rayform in every format the image target picks;
// - course command lines;
// - with SHARED_DIR: the course scenes and assets found there (under 1 MB),
//   bundled or converted the same way, at run time only.
// Input formats of the targets: docs/fuzzing.md.
#include "fuzz_targets.h"
#include "seed_files.h"
#include "rayform/image/image.h"
#include "rayform/scene/procedural_mesh.h"
#include "rayform/importers/scene_io.h"
#include "rayform/importers/scene_writer.h"

#include <meshoptimizer.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rayform;
using namespace rayform::fuzz;

namespace {

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string join(const std::vector<std::string>& parts) {
  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (i) s += fuzz::part_separator.substr(1);  // parts end with their newline
    s += parts[i];
    if (i + 1 < parts.size() && (s.empty() || s.back() != '\n')) s += '\n';
  }
  return s;
}

std::string obj_text(const Mesh& m) {
  std::ostringstream s;
  s << "o " << (m.name.empty() ? "mesh" : m.name) << "\nmtllib model.mtl\nusemtl tex\n";
  for (const vec3& p : m.positions) s << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const vec3& n : m.normals) s << "vn " << n.x << " " << n.y << " " << n.z << "\n";
  for (const vec2& t : m.uvs) s << "vt " << t.x << " " << t.y << "\n";
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    s << "f";
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.indices[i + k] + 1;
      s << " " << v;
      if (!m.uvs.empty() || !m.normals.empty()) s << "/" << (m.uvs.empty() ? "" : std::to_string(v));
      if (!m.normals.empty()) s << "/" << v;
    }
    s << "\n";
  }
  return s.str();
}

const char* mtl_text = "newmtl tex\nKd 1 0.8 0.6\nKs 0.3 0.3 0.3\nNs 40\nmap_Kd -s 2 2 1 tex.bmp\n";

std::string image_bytes(const std::string& ext, int w, int h) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.at(x, y);
      p[0] = float(x) / w, p[1] = float(y) / h, p[2] = float((x ^ y) & 1);
    }
  const fs::path p = out_root / ("tmp-image" + ext);
  write_image(p.string(), img);
  std::string bytes = read_file(p);
  fs::remove(p);
  return bytes;
}

// ---- glTF files made here ---------------------------------------------------

// EXT_meshopt_compression: attributes and triangles over a fallback buffer.
void meshopt_seeds(const GltfMesh& g) {
  const size_t nv = g.positions.size() / 3;
  std::string v(meshopt_encodeVertexBufferBound(nv, 12), '\0');
  v.resize(
      meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(v.data()), v.size(), g.positions.data(), nv, 12));
  std::string t(meshopt_encodeIndexBufferBound(g.indices.size(), nv), '\0');
  t.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(t.data()), t.size(), g.indices.data(),
                                     g.indices.size()));
  std::string bin = v;
  pad4(bin, '\0');
  const size_t t_at = bin.size();
  bin += t;
  std::ostringstream j;
  j << "{" << gltf_head
    << R"("extensionsUsed":["EXT_meshopt_compression"],"extensionsRequired":["EXT_meshopt_compression"],)"
    << R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
    << R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" << nv << R"(,"type":"VEC3",)" << minmax(g)
    << R"(},{"bufferView":1,"componentType":5125,"count":)" << g.indices.size() << R"(,"type":"SCALAR"}],)"
    << R"("bufferViews":[{"buffer":0,"byteLength":)" << nv * 12
    << R"(,"byteStride":12,"extensions":{"EXT_meshopt_compression":{"buffer":1,"byteLength":)" << v.size()
    << R"(,"byteStride":12,"count":)" << nv << R"(,"mode":"ATTRIBUTES"}}},)"
    << R"({"buffer":0,"byteOffset":)" << nv * 12 << R"(,"byteLength":)" << g.indices.size() * 4
    << R"(,"extensions":{"EXT_meshopt_compression":{"buffer":1,"byteOffset":)" << t_at << R"(,"byteLength":)"
    << t.size() << R"(,"byteStride":4,"count":)" << g.indices.size() << R"(,"mode":"TRIANGLES"}}}],)"
    << R"("buffers":[{"byteLength":)" << nv * 12 + g.indices.size() * 4
    << R"(,"extensions":{"EXT_meshopt_compression":{"fallback":true}}},{"byteLength":)" << bin.size() << R"(,"uri":")"
    << data_uri(bin) << "\"}]}";
  seed("gltf", "meshopt.gltf", j.str());
}

// KHR_mesh_quantization (normalised shorts, bytes), a sparse accessor,
// EXT_mesh_gpu_instancing and an embedded PNG with KHR_texture_transform.
void plain_seeds(const GltfMesh& g, const std::string& png) {
  const size_t nv = g.positions.size() / 3;
  std::vector<int16_t> qpos;
  for (size_t i = 0; i < g.positions.size(); ++i) qpos.push_back(int16_t(g.positions[i] * 32767.f));
  qpos.resize(nv * 4 / 4 * 3);
  std::vector<int16_t> qpos4;  // stride 8: xyz + padding
  for (size_t i = 0; i < nv; ++i) qpos4.insert(qpos4.end(), {qpos[3 * i], qpos[3 * i + 1], qpos[3 * i + 2], 0});
  std::vector<int8_t> qnrm;
  for (size_t i = 0; i < nv; ++i)
    qnrm.insert(qnrm.end(), {int8_t(g.normals[3 * i] * 127), int8_t(g.normals[3 * i + 1] * 127),
                             int8_t(g.normals[3 * i + 2] * 127), 0});
  std::vector<uint16_t> uv;
  for (size_t i = 0; i < nv; ++i) uv.insert(uv.end(), {uint16_t(i * 977 % 65536), uint16_t(i * 331 % 65536)});
  std::vector<uint16_t> idx(g.indices.begin(), g.indices.end());
  std::vector<float> sparse_values = {0.f, 2.f, 0.f};
  std::vector<uint16_t> sparse_indices = {0, 0};  // one index, padded
  std::vector<float> translations = {0, 0, 0, 3, 0, 0, 0, 3, 0};

  std::string bin;
  std::vector<std::pair<size_t, size_t>> views;
  for (const std::string& part : {bytes_of(qpos4), bytes_of(qnrm), bytes_of(uv), bytes_of(idx),
                                  bytes_of(sparse_indices), bytes_of(sparse_values), bytes_of(translations), png}) {
    pad4(bin, '\0');
    views.emplace_back(bin.size(), part.size());
    bin += part;
  }
  std::ostringstream j;
  j << "{" << gltf_head
    << R"("extensionsUsed":["KHR_mesh_quantization","EXT_mesh_gpu_instancing","KHR_texture_transform"],)"
    << R"("extensionsRequired":["KHR_mesh_quantization"],)"
    << R"("nodes":[{"mesh":0,"scale":[2,2,2],"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":5}}}},)"
    << R"({"mesh":1,"translation":[0,0,-3]}],)"
    << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"material":0}]},)"
    << R"({"primitives":[{"attributes":{"POSITION":4},"indices":3}]}],)"
    << R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":)"
    << R"({"offset":[0.5,0],"rotation":0.3,"scale":[2,2]}}},"metallicFactor":0.2},"doubleSided":true,)"
    << R"("alphaMode":"MASK","alphaCutoff":0.3}],)"
    << R"("textures":[{"source":0,"sampler":0}],"samplers":[{"wrapS":33648,"wrapT":33071,"magFilter":9728}],)"
    << R"("images":[{"bufferView":7,"mimeType":"image/png"}],)"
    << R"("accessors":[{"bufferView":0,"componentType":5122,"normalized":true,"count":)" << nv
    << R"(,"type":"VEC3","min":[-32767,-32767,-32767],"max":[32767,32767,32767]},)"
    << R"({"bufferView":1,"componentType":5120,"normalized":true,"count":)" << nv << R"(,"type":"VEC3"},)"
    << R"({"bufferView":2,"componentType":5123,"normalized":true,"count":)" << nv << R"(,"type":"VEC2"},)"
    << R"({"bufferView":3,"componentType":5123,"count":)" << idx.size() << R"(,"type":"SCALAR"},)"
    << R"({"componentType":5126,"count":)" << nv
    << R"(,"type":"VEC3","min":[-1,-1,-1],"max":[1,2,1],"sparse":{"count":1,)"
    << R"("indices":{"bufferView":4,"componentType":5123},"values":{"bufferView":5}}},)"
    << R"({"bufferView":6,"componentType":5126,"count":3,"type":"VEC3"}],"bufferViews":[)";
  const int strides[] = {8, 4, 4, 0, 0, 0, 0, 0};
  for (size_t i = 0; i < views.size(); ++i) {
    j << (i ? "," : "") << R"({"buffer":0,"byteOffset":)" << views[i].first << R"(,"byteLength":)" << views[i].second;
    if (strides[i]) j << R"(,"byteStride":)" << strides[i] << R"(,"target":34962)";
    j << "}";
  }
  j << "],";
  seed("gltf", "quantized_sparse_instanced.gltf",
       j.str() + R"("buffers":[{"byteLength":)" + std::to_string(bin.size()) + R"(,"uri":")" + data_uri(bin) + "\"}]}");
  seed("gltf", "quantized_sparse_instanced.glb",
       glb(j.str() + R"("buffers":[{"byteLength":)" + std::to_string(bin.size()) + "}]}", bin));
}

// The paths that allocate by a count the file declares: three nodes with
// their own morph weights (a mesh copy each), a morph target without a
// bufferView (zeros, one sparse value), and EXT_mesh_gpu_instancing with a
// SCALE accessor without a bufferView (zeros) beside a TRANSLATION one.
void count_seeds() {
  const std::vector<float> triangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<float> delta = {0, 0.5f, 0};
  const std::vector<uint8_t> target = {2, 0, 0, 0};  // vertex 2, padded
  const std::vector<float> translations = {0, 0, 0, 2, 0, 0};
  const std::string bin = bytes_of(triangle) + bytes_of(delta) + bytes_of(target) + bytes_of(translations);
  std::ostringstream j;
  j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2,3]}],)"
    << R"("extensionsUsed":["EXT_mesh_gpu_instancing"],)"
    << R"("nodes":[{"mesh":0,"weights":[0.5]},{"mesh":0,"weights":[1],"translation":[0,0,-1]},)"
    << R"({"mesh":0,"translation":[0,0,-2]},)"
    << R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":2,"SCALE":3}}}}],)"
    << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}],"weights":[0]}],)"
    << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
    << R"({"componentType":5126,"count":3,"type":"VEC3","sparse":{"count":1,)"
    << R"("indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":1}}},)"
    << R"({"bufferView":3,"componentType":5126,"count":2,"type":"VEC3"},)"
    << R"({"componentType":5126,"count":2,"type":"VEC3"}],)"
    << R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12},)"
    << R"({"buffer":0,"byteOffset":48,"byteLength":4},{"buffer":0,"byteOffset":52,"byteLength":24}],)"
    << R"("buffers":[{"byteLength":)" << bin.size() << R"(,"uri":")" << data_uri(bin) << "\"}]}";
  seed("gltf", "counts_morph_instancing_unbacked.gltf", j.str());
}

// A scene through rayform's writers: embedded .gltf and .glb.
void converted_seeds(const Scene& scene, const std::string& name) {
  for (const char* ext : {".gltf", ".glb"}) {
    const fs::path p = out_root / ("tmp-convert" + std::string(ext));
    try {
      SaveOptions o;
      o.embed = true;
      o.sphere_segments = 8;
      SaveResult r = save_scene(scene, p.string(), o);
      seed("gltf", name + ext, read_file(p));
      for (const std::string& f : r.files) fs::remove(f);
    } catch (const std::exception& e) {
      std::cerr << "seeds: " << name << ext << ": " << e.what() << "\n";
    }
  }
}

// A course scene as a bundle: its first mesh and texture become mesh.obj and tex.*.
void course_seed(const fs::path& scene_path, const std::string& name) {
  std::string text = read_file(scene_path);
  std::smatch m;
  std::string mesh, texture, texture_ext = ".bmp";
  static const std::regex mesh_re(R"((obj_file\s+)(\S+))"), tex_re(R"((texture\s+)(\S+))");
  if (std::regex_search(text, m, mesh_re)) mesh = read_file(scene_path.parent_path() / m[2].str());
  if (std::regex_search(text, m, tex_re)) {
    texture = read_file(scene_path.parent_path() / m[2].str());
    texture_ext = fs::path(m[2].str()).extension().string();
  }
  text = std::regex_replace(text, mesh_re, "$1mesh.obj");
  text = std::regex_replace(text, tex_re, "$1tex" + texture_ext);
  seed("course_txt", name, mesh.empty() && texture.empty() ? text : join({text, mesh, texture}));
  try {
    converted_seeds(load_scene(scene_path.string()).scene, name);
  } catch (const std::exception& e) {
    std::cerr << "seeds: " << name << ": " << e.what() << "\n";
  }
}

void obj_seed(const fs::path& obj_path, const std::string& name) {
  std::string text = read_file(obj_path), mtl, texture;
  std::smatch m;
  static const std::regex mtl_re(R"((mtllib\s+)(\S+))"), tex_re(R"((map_Kd\s+)(\S+))");
  if (std::regex_search(text, m, mtl_re)) {
    const fs::path mtl_path = obj_path.parent_path() / m[2].str();
    mtl = read_file(mtl_path);
    std::smatch t;
    if (std::regex_search(mtl, t, tex_re)) texture = read_file(mtl_path.parent_path() / t[2].str());
    mtl = std::regex_replace(mtl, tex_re, "$1tex" + fs::path(t[2].str()).extension().string());
  }
  text = std::regex_replace(text, mtl_re, "$1model.mtl");
  seed("obj", name, join({text, mtl, texture}));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: rayform_fuzz_seeds SOURCE_DIR OUT [SHARED_DIR]\n";
    return 2;
  }
  const fs::path source = argv[1];
  out_root = argv[2];
  fs::create_directories(out_root);

  // Images: every extension the image target picks, in its selector order.
  const char* exts[] = {".bmp", ".png", ".tga", ".jpg", ".jpeg", ".hdr",
                        ".gif", ".ppm", ".pgm", ".psd", ".exr",  ".tif"};
  std::string bmp;
  for (size_t i = 0; i < std::size(exts); ++i) {
    std::string bytes;
    try {
      bytes = image_bytes(exts[i], 7, 5);
    } catch (const std::exception&) {
      continue;  // formats rayform reads but does not write (gif, psd, ...)
    }
    if (i == 0) bmp = bytes;
    seed("image", std::string("generated") + exts[i], std::string(1, char(i)) + bytes);
  }
  const std::string png = image_bytes(".png", 4, 4);
  for (const auto& e : fs::directory_iterator(source / "scenes/assets")) {
    const std::string ext = e.path().extension().string();
    for (size_t i = 0; i < std::size(exts); ++i)
      if (ext == exts[i]) seed("image", "own_" + e.path().filename().string(), char(i) + read_file(e.path()));
  }

  // Course scenes and OBJ files of our own.
  for (const fs::path& dir : {source / "scenes", source / "scenes/tests"})
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".txt") course_seed(e.path(), "own_" + e.path().stem().string() + ".txt");
  for (const auto& e : fs::directory_iterator(source / "scenes/assets")) {
    if (e.path().extension() == ".obj") obj_seed(e.path(), "own_" + e.path().filename().string());
    if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") {
      try {
        converted_seeds(load_scene(e.path().string()).scene, "own_" + e.path().stem().string());
      } catch (const std::exception& x) {
        std::cerr << "seeds: " << e.path() << ": " << x.what() << "\n";
      }
    }
  }

  // Generated meshes.
  const Mesh meshes[] = {make_cube(), make_icosphere(1), make_grid(3, 2), make_bumpy_torus(200)};
  for (size_t i = 0; i < std::size(meshes); ++i)
    seed("obj", "generated_" + std::to_string(i) + ".obj", join({obj_text(meshes[i]), mtl_text, bmp}));
  const GltfMesh sphere = gltf_mesh(make_icosphere(1));
  meshopt_seeds(sphere);
  plain_seeds(sphere, png);
  count_seeds();

  // Course command lines.
  using namespace std::string_literals;
  const std::string lines[] = {
      "-input scene.txt -size 200 200 -output out.bmp",
      "-input s.txt -size 64 48 -output o.png -depth 8 12 d.bmp -normals n.bmp -dialect 2012",
      "-input s.txt -size 10 10 -output o.exr -dialect 2019 -bounces 4 -shadows -albedo a.png",
      "-input s.txt -size 10 10 -output o.tga -jitter -filter -spp 4 -threads 1 -quiet -stats -generic",
      "-input\0s.txt\0-size\0003\0004\0-output\0o.jpg"s,
  };
  for (size_t i = 0; i < std::size(lines); ++i) seed("course_args", "line" + std::to_string(i), lines[i]);

  // Third-party data, at run time only.
  if (argc > 3 && fs::is_directory(argv[3])) {
    const fs::path shared = argv[3];
    int n = 0;
    for (const auto& e : fs::recursive_directory_iterator(shared)) {
      if (!e.is_regular_file() || e.file_size() > (size_t(1) << 20)) continue;
      const fs::path& p = e.path();
      const std::string ext = p.extension().string();
      const std::string name = "shared_" + std::to_string(n++) + "_" + p.filename().string();
      if (ext == ".txt" && p.string().find("/course/") != std::string::npos) course_seed(p, name);
      else if (ext == ".obj") obj_seed(p, name);
      else if (ext == ".glb") seed("gltf", name, read_file(p));
      else if (ext == ".gltf") {
        try {
          converted_seeds(load_scene(p.string()).scene, name);
        } catch (const std::exception& x) {
          std::cerr << "seeds: " << p << ": " << x.what() << "\n";
        }
      }
    }
  }
  std::cout << written << " seed files in " << out_root.string() << "\n";
}
