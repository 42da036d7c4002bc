#include "scene_writer.h"

#include "course_txt/course_writer.h"
#include "gltf/gltf_writer.h"
#include "image/image.h"
#include "obj/obj_writer.h"
#include "scene/error.h"
#include "scene/file_extension.h"
#include "scene/node_walk.h"
#include "scene/scene_stats.h"
#include "scene_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <system_error>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;

// ---- entry point ------------------------------------------------------------------

SaveResult save_scene(const Scene& scene, const std::string& path, const SaveOptions& options,
                      std::vector<std::string>* messages) {
  const std::string ext = lower_extension(path);
  if (ext != ".txt" && ext != ".obj" && ext != ".gltf" && ext != ".glb")
    throw Error(path + ": cannot write scenes of type '" + ext + "': expected .txt (course), .obj, .gltf or .glb");
  if (options.sphere_segments < 3)
    throw Error(path + ": sphere segments must be at least 3, got " + std::to_string(options.sphere_segments));
  fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw Error(path + ": cannot write: folder '" + dir.string() + "' does not exist");
  if (fs::is_directory(path, ec)) throw Error(path + ": cannot write: it is a folder");
  if (scene.root == invalid) throw Error(path + ": the scene has no root node: nothing to write");

  const std::string name = fs::path(path).filename().string();
  Scene flat;
  const Scene* s = &scene;
  if (options.flatten) {
    flat = flatten_scene(scene, options.sphere_segments, name, messages);
    s = &flat;
  }
  if (ext == ".txt") {
    CourseWriteOptions o;
    o.dialect = options.dialect;
    return write_course_scene(*s, path, o, messages);
  }
  if (ext == ".obj") {
    ObjWriteOptions o;
    o.sphere_segments = options.sphere_segments;
    o.flattened = options.flatten;
    return write_obj_scene(*s, path, o, messages);
  }
  GltfWriteOptions o;
  o.binary = ext == ".glb";
  o.embed = options.embed;
  o.sphere_segments = options.sphere_segments;
  o.shape_extras = options.shape_extras;
  return write_gltf_scene(*s, path, o, messages);
}

// ---- tessellation ---------------------------------------------------------------------

Mesh tessellate_sphere(const Sphere& sphere, int segments) {
  segments = std::max(segments, 3);
  const int bands = std::max(2, segments / 2);
  Mesh m;
  m.name = "sphere";
  auto add = [&](vec3 dir) {
    m.positions.push_back(sphere.center + sphere.radius * dir);
    m.normals.push_back(dir);
  };
  // Angles in double so that the rings are symmetric to the last bit.
  add(vec3(0.f, 1.f, 0.f));  // north pole: vertex 0
  for (int i = 1; i < bands; ++i) {
    const double theta = M_PI * double(i) / double(bands);
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * M_PI * double(j) / double(segments);
      dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      add(vec3(glm::normalize(d)));
    }
  }
  add(vec3(0.f, -1.f, 0.f));  // south pole: last vertex
  const uint32_t south = uint32_t(m.positions.size() - 1);
  auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * segments + (j % segments)); };
  // Seen from outside, with phi growing counter-clockwise about +y seen from
  // above (x -> -z), triangles (pole, ring j, ring j+1) face outwards.
  for (int j = 0; j < segments; ++j) m.indices.insert(m.indices.end(), {0u, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < bands; ++i)
    for (int j = 0; j < segments; ++j) {
      uint32_t a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  for (int j = 0; j < segments; ++j)
    m.indices.insert(m.indices.end(), {south, ring(bands - 1, j + 1), ring(bands - 1, j)});
  return m;
}

Mesh plane_quad(const Plane& plane, vec3 around, float half_size) {
  vec3 n = glm::normalize(plane.normal);
  const float d = plane.offset / glm::length(plane.normal);
  // Tangents from the axis least aligned with n.
  vec3 a = std::abs(n.x) < 0.9f ? vec3(1.f, 0.f, 0.f) : vec3(0.f, 1.f, 0.f);
  vec3 t = glm::normalize(glm::cross(a, n));
  vec3 b = glm::cross(n, t);
  vec3 c = around - (glm::dot(n, around) - d) * n;
  // Snap the centre onto the plane along the dominant normal axis, so that an
  // axis-aligned plane's vertices satisfy n . p = d exactly.
  int k = max_dimension(glm::abs(n));
  if (std::abs(n[k]) == 1.f) c[k] = d * n[k];
  Mesh m;
  m.name = "plane";
  vec3 corners[4] = {c - half_size * t - half_size * b, c + half_size * t - half_size * b,
                     c + half_size * t + half_size * b, c - half_size * t + half_size * b};
  for (vec3 p : corners) {
    if (std::abs(n[k]) == 1.f) p[k] = c[k];
    m.positions.push_back(p);
    m.normals.push_back(n);
  }
  // (t, b, n) is right-handed: 0,1,2 is counter-clockwise seen from +n.
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Bounds3 scene_extent(const Scene& scene) {
  Bounds3 b;
  if (scene.root != invalid) b = scene_stats(scene).bounds;
  for (const Camera& c : scene.cameras) b.expand(c.center);
  for (const Light& l : scene.lights)
    if (l.kind != Light::Kind::directional) b.expand(l.position);
  return b;
}

// ---- flattening ---------------------------------------------------------------------------

namespace {

// Whether the linear part of m is a rotation times a uniform scale s (> 0).
bool is_similarity(const mat4& m, float* scale) {
  vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  float l0 = glm::length(c0), l1 = glm::length(c1), l2 = glm::length(c2);
  float s = (l0 + l1 + l2) / 3.f;
  if (!(s > 0.f)) return false;
  const float tol = 1e-5f;
  if (std::abs(l0 - s) > tol * s || std::abs(l1 - s) > tol * s || std::abs(l2 - s) > tol * s) return false;
  if (std::abs(glm::dot(c0, c1)) > tol * s * s || std::abs(glm::dot(c1, c2)) > tol * s * s ||
      std::abs(glm::dot(c0, c2)) > tol * s * s)
    return false;
  *scale = s;
  return true;
}

}  // namespace

Mesh transform_mesh(const Mesh& src, const mat4& m) {
  Mesh out = src;
  const mat3 nm = glm::transpose(glm::inverse(mat3(m)));
  for (vec3& p : out.positions) p = transform_point(m, p);
  for (vec3& n : out.normals) {
    vec3 t = nm * n;
    float len = glm::length(t);
    n = len > 0.f ? t / len : vec3(0.f);
  }
  if (glm::determinant(mat3(m)) < 0.f)
    for (size_t i = 0; i + 2 < out.indices.size(); i += 3) std::swap(out.indices[i + 1], out.indices[i + 2]);
  return out;
}

Plane transform_plane(const Plane& p, const mat4& m) {
  vec3 nn = glm::normalize(p.normal);
  vec3 on = nn * (p.offset / glm::length(p.normal));
  vec3 wn = glm::normalize(glm::transpose(glm::inverse(mat3(m))) * nn);
  return Plane{wn, glm::dot(wn, transform_point(m, on))};
}

Scene flatten_scene(const Scene& scene, int sphere_segments, const std::string& name,
                    std::vector<std::string>* messages) {
  Scene out;
  out.source_path = scene.source_path;
  out.cameras = scene.cameras;
  out.lights = scene.lights;
  out.materials = scene.materials;
  out.textures = scene.textures;
  out.background = scene.background;
  Node root;
  root.kind = Node::Kind::group;
  root.name = scene.root != invalid ? scene.nodes[size_t(scene.root)].name : "root";
  std::vector<Node> shapes;
  std::map<int, int> shared_meshes;  // untransformed meshes keep one copy
  size_t tessellated = 0;
  for_each_shape_node(scene, [&](const Node& n, const mat4& m) {
    if (n.shape < 0) return;
    Node s;
    s.kind = Node::Kind::shape;
    s.name = n.name;
    s.material = n.material;
    s.shape_kind = n.shape_kind;
    switch (n.shape_kind) {
      case ShapeKind::sphere: {
        const Sphere& sp = scene.spheres.at(size_t(n.shape));
        float k = 1.f;
        if (is_similarity(m, &k)) {
          out.spheres.push_back(Sphere{transform_point(m, sp.center), sp.radius * k});
          s.shape = int(out.spheres.size()) - 1;
        } else {
          Mesh mesh = transform_mesh(tessellate_sphere(sp, sphere_segments), m);
          out.meshes.push_back(std::move(mesh));
          s.shape_kind = ShapeKind::mesh;
          s.shape = int(out.meshes.size()) - 1;
          ++tessellated;
        }
        break;
      }
      case ShapeKind::plane: {
        out.planes.push_back(is_identity(m) ? scene.planes.at(size_t(n.shape))
                                            : transform_plane(scene.planes.at(size_t(n.shape)), m));
        s.shape = int(out.planes.size()) - 1;
        break;
      }
      case ShapeKind::triangle: {
        Triangle t = scene.triangles.at(size_t(n.shape));
        for (vec3& v : t.vertices) v = transform_point(m, v);
        if (glm::determinant(mat3(m)) < 0.f) std::swap(t.vertices[1], t.vertices[2]);
        out.triangles.push_back(t);
        s.shape = int(out.triangles.size()) - 1;
        break;
      }
      case ShapeKind::mesh: {
        if (is_identity(m)) {
          auto it = shared_meshes.find(n.shape);
          if (it == shared_meshes.end()) {
            out.meshes.push_back(scene.meshes.at(size_t(n.shape)));
            it = shared_meshes.emplace(n.shape, int(out.meshes.size()) - 1).first;
          }
          s.shape = it->second;
        } else {
          out.meshes.push_back(transform_mesh(scene.meshes.at(size_t(n.shape)), m));
          s.shape = int(out.meshes.size()) - 1;
        }
        break;
      }
    }
    shapes.push_back(std::move(s));
  });
  for (Node& s : shapes) {
    out.nodes.push_back(std::move(s));
    root.children.push_back(int(out.nodes.size()) - 1);
  }
  out.nodes.push_back(std::move(root));
  out.root = int(out.nodes.size()) - 1;
  if (tessellated && messages)
    messages->push_back(name + ": --flatten: " + std::to_string(tessellated) +
                        " sphere(s) under a non-uniform scale or shear became triangle meshes (" +
                        std::to_string(sphere_segments) + " segments)");
  return out;
}

MeshTotals mesh_totals(const Scene& scene) {
  MeshTotals t;
  for (const Mesh& m : scene.meshes) {
    t.vertices += m.positions.size();
    t.uvs += m.uvs.size();
    t.normals += m.normals.size();
    t.triangles += m.triangle_count();
  }
  return t;
}

// ---- text -----------------------------------------------------------------------------------

std::string format_float(float v) {
  if (v == 0.f) return "0";  // also -0
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string format_vec3(vec3 v) { return format_float(v.x) + " " + format_float(v.y) + " " + format_float(v.z); }

std::string quoted_list(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& x : names) out += (out.empty() ? "'" : ", '") + x + "'";
  return out;
}

std::string safe_file_name(const std::string& name) {
  std::string out;
  for (char c : name) {
    bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
              c == '-';
    out += ok ? c : '_';
  }
  while (!out.empty() && out[0] == '.') out[0] = '_';  // no hidden files
  return out.empty() ? std::string("unnamed") : out;
}

std::string texture_base_name(const Texture& t) {
  std::string n = !t.name.empty() ? t.name : (!t.path.empty() ? t.path : std::string("texture"));
  std::replace(n.begin(), n.end(), '\\', '/');
  std::string stem = fs::path(n).stem().string();
  return stem.empty() ? std::string("texture") : stem;
}

// ---- images ----------------------------------------------------------------------------------

std::vector<uint8_t> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path + ": cannot read file");
  return bytes;
}

Pixels8 texture_pixels(const Texture& t) {
  Pixels8 p;
  if (!t.pixels.empty()) {
    p.width = t.width;
    p.height = t.height;
    p.channels = t.channels;
    if (p.width <= 0 || p.height <= 0 || p.channels < 1 || p.channels > 4 ||
        t.pixels.size() != size_t(p.width) * size_t(p.height) * size_t(p.channels))
      throw Error("texture '" + t.name + "': inconsistent pixel data");
    p.data = t.pixels;
    return p;
  }
  if (t.path.empty()) throw Error("texture '" + t.name + "': neither pixels nor a file");
  std::vector<uint8_t> bytes = read_file_bytes(t.path);
  int w = 0, h = 0, c = 0;
  if (unsigned char* d = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &c, 0)) {
    p.width = w;
    p.height = h;
    p.channels = c;
    p.data.assign(d, d + size_t(w) * size_t(h) * size_t(c));
    stbi_image_free(d);
    return p;
  }
  // Formats stb does not read (tiff, exr, ...): through the image module.
  Image img = read_image(t.path);
  p.width = img.width;
  p.height = img.height;
  p.channels = std::min(img.channels, 4);
  p.data.resize(size_t(p.width) * size_t(p.height) * size_t(p.channels));
  for (size_t i = 0, n = size_t(p.width) * size_t(p.height); i < n; ++i)
    for (int k = 0; k < p.channels; ++k)
      p.data[i * size_t(p.channels) + size_t(k)] = uint8_t(
          std::lround(std::clamp(img.pixels[i * size_t(img.channels) + size_t(k)], 0.f, 1.f) * 255.f));
  return p;
}

namespace {
void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const uint8_t* b = static_cast<const uint8_t*>(data);
  out->insert(out->end(), b, b + size);
}
}  // namespace

std::vector<uint8_t> encode_png(const Pixels8& p) {
  std::vector<uint8_t> out;
  if (!stbi_write_png_to_func(append_bytes, &out, p.width, p.height, p.channels, p.data.data(),
                              p.width * p.channels))
    throw Error("cannot encode a PNG image");
  return out;
}

std::vector<uint8_t> encode_bmp(const Pixels8& p) {
  // 24-bit BMP: the course reads no other kind.
  std::vector<uint8_t> rgb(size_t(p.width) * size_t(p.height) * 3);
  for (size_t i = 0, n = size_t(p.width) * size_t(p.height); i < n; ++i)
    for (int k = 0; k < 3; ++k)
      rgb[i * 3 + size_t(k)] = p.data[i * size_t(p.channels) + size_t(p.channels >= 3 ? k : 0)];
  std::vector<uint8_t> out;
  if (!stbi_write_bmp_to_func(append_bytes, &out, p.width, p.height, 3, rgb.data()))
    throw Error("cannot encode a BMP image");
  return out;
}

std::vector<uint8_t> texture_file(const Texture& t, const std::vector<std::string>& wanted, std::string* ext) {
  if (!t.path.empty()) {
    std::string e = lower_extension(t.path);
    if (!e.empty()) e = e.substr(1);
    if (e == "jpeg") e = "jpg";
    std::error_code ec;
    if (std::find(wanted.begin(), wanted.end(), e) != wanted.end() && fs::is_regular_file(t.path, ec)) {
      *ext = e;
      return read_file_bytes(t.path);
    }
  }
  Pixels8 p = texture_pixels(t);
  *ext = wanted.at(0);
  return *ext == "bmp" ? encode_bmp(p) : encode_png(p);
}

// ---- output files ------------------------------------------------------------------------------

OutputFiles::OutputFiles(std::string main) : main_(std::move(main)) {}

OutputFiles::~OutputFiles() {
  std::error_code ec;
  for (const std::string& t : temps_) fs::remove(t, ec);
  for (const std::string& d : temp_dirs_) fs::remove_all(d, ec);
}

std::string OutputFiles::beside(const std::string& file_name) const {
  return (fs::path(main_).parent_path() / file_name).string();
}

void OutputFiles::add(const std::string& path, std::vector<uint8_t> bytes) {
  for (Entry& e : entries_)
    if (e.path == path) {
      e.bytes = std::move(bytes);
      e.temp.clear();
      return;
    }
  entries_.push_back(Entry{path, std::move(bytes), {}});
}

void OutputFiles::add(const std::string& path, const std::string& text) {
  add(path, std::vector<uint8_t>(text.begin(), text.end()));
}

void OutputFiles::add_written(const std::string& path, const std::string& temp_path) {
  temps_.push_back(temp_path);
  for (Entry& e : entries_)
    if (e.path == path) {
      e.bytes.clear();
      e.temp = temp_path;
      return;
    }
  entries_.push_back(Entry{path, {}, temp_path});
}

bool OutputFiles::has(const std::string& path) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.path == path; });
}

namespace {
std::string temp_name_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  fs::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter++)))
      .string();
}
}  // namespace

std::string OutputFiles::temp_dir() {
  std::string d = temp_name_for(main_) + ".d";
  std::error_code ec;
  fs::create_directories(d, ec);
  if (ec) throw Error(main_ + ": cannot create a temporary folder '" + d + "': " + ec.message());
  temp_dirs_.push_back(d);
  return d;
}

std::vector<std::string> OutputFiles::commit() {
  // Main file last: readers never see it before what it names.
  std::stable_partition(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.path != main_; });
  std::vector<std::pair<std::string, std::string>> moves;  // temp -> final
  for (const Entry& e : entries_) {
    if (!e.temp.empty()) {
      moves.emplace_back(e.temp, e.path);
      continue;
    }
    std::string tmp = temp_name_for(e.path);
    temps_.push_back(tmp);
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw Error(e.path + ": cannot write (cannot create '" + tmp + "')");
      out.write(reinterpret_cast<const char*>(e.bytes.data()), std::streamsize(e.bytes.size()));
      out.flush();
      if (!out) throw Error(e.path + ": cannot write (disk full or I/O error)");
    }
    moves.emplace_back(tmp, e.path);
  }
  std::vector<std::string> done;
  for (const auto& [from, to] : moves) {
    std::error_code ec;
    fs::rename(from, to, ec);
    if (ec) throw Error(to + ": cannot write (rename from '" + from + "' failed: " + ec.message() + ")");
    temps_.erase(std::remove(temps_.begin(), temps_.end(), from), temps_.end());
    done.push_back(to);
  }
  std::rotate(done.begin(), done.end() - (done.empty() ? 0 : 1), done.end());  // main first
  return done;
}

}  // namespace rayform
