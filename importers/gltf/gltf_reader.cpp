#include "gltf/gltf_reader.h"

#include "gltf/gltf_writer.h"
#include "scene/error.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace rayform {
namespace fs = std::filesystem;

UvTransform gltf_uv_transform_to_scene(vec2 offset, float rotation, vec2 scale) {
  // glTF: M(x) = o + R(r) S x with R(r) = [[cos r, sin r], [-sin r, cos r]]
  // (rows; the matrix the shader applies, and the one under which the
  // KHR_texture_transform sample model's "Correct" markers line up).
  // Scene uvs are F(x) = (x.u, 1 - x.v) of glTF's, and the sampler reads
  // v = 1 at the top, so the stored transform is M' = F M F:
  //   M'(x) = D R(r) S D x + D (R(r) S e + o) + e,  D = diag(1, -1), e = (0, 1)
  // and D R(r) D = R(-r), S D = D S; R(r) S e = (sin r s.y, cos r s.y).
  UvTransform t;
  t.scale = scale;
  t.rotation = -rotation;
  t.offset = vec2(offset.x + std::sin(rotation) * scale.y, 1.f - offset.y - std::cos(rotation) * scale.y);
  return t;
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- small helpers ----------------------------------------------------------

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  size_t e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// tinygltf's multi-line messages as one line.
std::string one_line(const std::string& s) {
  std::istringstream in(s);
  std::string line, out;
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty()) continue;
    out += (out.empty() ? "" : "; ") + line;
  }
  return out;
}

std::string idx(const char* array, long i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
  }
  return "unknown type";
}

const char* component_name(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
  }
  return "unknown component type";
}

int component_size(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
  }
  return 0;
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
  }
  return 0;
}

// One component as float; normalised integers map to [0, 1] or [-1, 1].
float read_component(const unsigned char* p, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.f, -1.f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.f, -1.f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
  }
  return 0.f;
}

uint32_t read_index(const unsigned char* p, int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
  return 0;
}

// a + b <= limit without overflow.
bool fits(uint64_t a, uint64_t b, uint64_t limit) { return a <= limit && b <= limit - a; }

std::string percent_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// ---- tinygltf callbacks -------------------------------------------------------

// File access for tinygltf: only below the model's folder (tinygltf would
// also look in the working directory), no path expansion.
struct FsContext {
  std::string base;  // the model's folder, as passed to tinygltf
};

bool fs_file_exists(const std::string& path, void* user) {
  const FsContext* ctx = static_cast<const FsContext*>(user);
  if (path.rfind(ctx->base + "/", 0) != 0) return false;
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string fs_expand(const std::string& path, void*) { return path; }

bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (err) *err += "cannot open " + path;
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported by the reader";
  return false;
}

struct ImageContext {
  const tinygltf::Model* model = nullptr;
  std::vector<std::string> warnings;
};

// Decodes an image to RGBA8 with tinygltf's own loader, after checking the
// byte range tinygltf takes from a bufferView (it does not). An image that
// cannot be decoded is a warning: the asset still loads, untextured there.
bool load_image(tinygltf::Image* image, const int image_idx, std::string* err, std::string* warn, int, int,
                const unsigned char* bytes, int size, void* user) {
  ImageContext* ctx = static_cast<ImageContext*>(user);
  std::string where = idx("images", image_idx);
  if (image->bufferView >= 0) {
    const tinygltf::Model& m = *ctx->model;
    // tinygltf checked both indices before calling.
    const tinygltf::BufferView& bv = m.bufferViews[size_t(image->bufferView)];
    const tinygltf::Buffer& buf = m.buffers[size_t(bv.buffer)];
    if (!fits(bv.byteOffset, bv.byteLength, buf.data.size())) {
      if (err)
        *err += where + ": " + idx("bufferViews", image->bufferView) + " (offset " + std::to_string(bv.byteOffset) +
                ", length " + std::to_string(bv.byteLength) + ") lies past the end of " + idx("buffers", bv.buffer) +
                " (" + std::to_string(buf.data.size()) + " bytes)";
      return false;
    }
  }
  if (bytes == nullptr || size <= 0) {
    ctx->warnings.push_back(where + ": no image data; textures using it are dropped");
    return true;
  }
  std::string e, w;
  if (!tinygltf::LoadImageData(image, image_idx, &e, &w, 0, 0, bytes, size, nullptr)) {
    ctx->warnings.push_back(where + (image->uri.empty() || is_data_uri(image->uri) ? "" : " ('" + image->uri + "')") +
                            ": cannot decode (" + one_line(e) + "); textures using it are dropped");
    image->image.clear();
    image->width = image->height = -1;
    return true;
  }
  if (warn && !w.empty()) *warn += w;
  if (image->bits == 16) {  // keep the high byte: the Scene holds 8-bit texels
    std::vector<unsigned char> eight(image->image.size() / 2);
    for (size_t i = 0; i < eight.size(); ++i) {
      uint16_t v;
      std::memcpy(&v, &image->image[2 * i], 2);
      eight[i] = static_cast<unsigned char>(v >> 8);
    }
    image->image = std::move(eight);
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  }
  return true;
}

// ---- the reader ---------------------------------------------------------------

// Extensions whose data this reader uses. Any other in extensionsRequired is an error.
const std::set<std::string>& supported_extensions() {
  static const std::set<std::string> s = {"KHR_texture_transform", "KHR_lights_punctual",
                                          "KHR_materials_emissive_strength"};
  return s;
}

struct Primitive {
  int mesh = invalid;      // Scene mesh
  int material = invalid;  // Scene material
};

class GltfSceneBuilder {
 public:
  GltfSceneBuilder(const std::string& path, const GltfReadOptions& options, std::vector<std::string>* warnings)
      : path_(path), options_(options), warnings_(warnings) {}

  Scene build() {
    load();
    check_asset();
    scene_.source_path = path_;
    meshes_.resize(model_.meshes.size());
    mesh_done_.assign(model_.meshes.size(), 0);
    materials_.assign(model_.materials.size(), invalid);
    textures_.assign(model_.textures.size(), -2);
    nodes_.assign(model_.nodes.size(), invalid);
    on_path_.assign(model_.nodes.size(), 0);

    // Every material in file order, so that Scene material i is glTF material i
    // (the default material, if some primitive needs it, comes after them).
    for (size_t i = 0; i < model_.materials.size(); ++i) material(int(i), idx("materials", long(i)));

    Node root;
    root.kind = Node::Kind::group;
    root.name = fs::path(path_).stem().string();
    for (const auto& [node, ref] : root_nodes()) root.children.push_back(convert_node(node, ref, mat4(1.f)));
    scene_.nodes.push_back(std::move(root));
    scene_.root = int(scene_.nodes.size()) - 1;

    if (!unused_textures_.empty()) {
      std::string list;
      for (const std::string& u : unused_textures_) list += (list.empty() ? "" : ", ") + u;
      warn("materials use " + list + ", which the Phong shader does not use; ignored");
    }
    if (!model_.animations.empty()) warn("animations are ignored: the scene is read in its static pose");
    if (!model_.skins.empty()) warn("skins are ignored: skinned meshes are drawn in their bind pose");
    apply_rayform_extras();
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(path_ + ": " + what); }

  void warn(const std::string& w) {
    std::string full = path_ + ": " + w;
    if (warnings_ && seen_warnings_.insert(full).second) warnings_->push_back(full);
  }

  // ---- loading --------------------------------------------------------------

  void load() {
    std::vector<unsigned char> bytes;
    {
      std::ifstream in(path_, std::ios::binary);
      if (!in) fail("cannot open glTF file");
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (in.bad()) fail("cannot read glTF file");
    }
    if (bytes.empty()) fail("not a glTF file: the file is empty");
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) fail("file too large for a glTF (4 GiB or more)");
    const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    if (!glb) {
      size_t first = 0;
      while (first < bytes.size() && std::isspace(bytes[first])) ++first;
      // A UTF-8 byte order mark is tolerated.
      if (first + 3 <= bytes.size() && bytes[first] == 0xEF && bytes[first + 1] == 0xBB && bytes[first + 2] == 0xBF)
        first += 3;
      if (first >= bytes.size() || bytes[first] != '{')
        fail("not a glTF file: neither a JSON object nor a binary glTF (GLB) container");
    }

    FsContext fsctx;
    fsctx.base = fs::path(path_).parent_path().string();
    if (fsctx.base.empty()) fsctx.base = ".";
    tinygltf::FsCallbacks callbacks{&fs_file_exists, &fs_expand, &fs_read, &fs_write, &fsctx};
    ImageContext images;
    images.model = &model_;

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(callbacks);
    loader.SetImageLoader(&load_image, &images);
    std::string err, warn_text;
    bool ok = glb ? loader.LoadBinaryFromMemory(&model_, &err, &warn_text, bytes.data(), unsigned(bytes.size()),
                                                fsctx.base)
                  : loader.LoadASCIIFromString(&model_, &err, &warn_text, reinterpret_cast<const char*>(bytes.data()),
                                               unsigned(bytes.size()), fsctx.base);
    if (!ok) diagnose_load_failure(bytes, glb, err);
    for (const std::string& w : images.warnings) warn(w);
    std::istringstream wl(warn_text);
    std::string l;
    while (std::getline(wl, l)) {
      l = trim(l);
      if (l.empty()) continue;
      // Missing image files: tinygltf says "File not found : x.png" then
      // "Failed to load external 'uri' for image[0] ...": say it once, plainly.
      if (l.rfind("File not found : ", 0) == 0) {
        warn("cannot find image file '" + l.substr(17) + "'; textures using it are dropped");
        continue;
      }
      if (l.rfind("Failed to load external 'uri' for image", 0) == 0) continue;
      warn(l);
    }
  }

  // Turns tinygltf's message into one that names the element at fault.
  [[noreturn]] void diagnose_load_failure(const std::vector<unsigned char>& bytes, bool glb, const std::string& err) {
    std::string e = one_line(err);
    if (glb && (e.find("Invalid glTF binary") != std::string::npos || e.find("Too short") != std::string::npos ||
                e.find("Chunk") != std::string::npos || e.find("Invalid magic") != std::string::npos))
      fail("not a valid binary glTF (GLB): " + e);
    // Which buffer is missing? tinygltf reports only the file name.
    if (e.find("File not found") != std::string::npos || e.find("File size mismatch") != std::string::npos ||
        e.find("File is empty") != std::string::npos) {
      try {
        std::string json_text;
        if (glb) {
          uint32_t len = 0;
          if (bytes.size() >= 20) std::memcpy(&len, bytes.data() + 12, 4);
          if (bytes.size() >= 20 && len <= bytes.size() - 20) json_text.assign(bytes.begin() + 20, bytes.begin() + 20 + len);
        } else {
          json_text.assign(bytes.begin(), bytes.end());
        }
        nlohmann::json j = nlohmann::json::parse(json_text);
        if (j.contains("buffers") && j["buffers"].is_array()) {
          fs::path dir = fs::path(path_).parent_path();
          for (size_t i = 0; i < j["buffers"].size(); ++i) {
            const auto& b = j["buffers"][i];
            if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
            std::string uri = b["uri"].get<std::string>();
            if (is_data_uri(uri)) continue;
            fs::path file = dir / percent_decode(uri);
            std::error_code ec;
            if (!fs::is_regular_file(file, ec))
              fail(idx("buffers", long(i)) + ": cannot find '" + uri + "' (looked in " +
                   (dir.empty() ? std::string(".") : dir.string()) + ")");
            uintmax_t size = fs::file_size(file, ec);
            if (b.contains("byteLength") && b["byteLength"].is_number_unsigned() &&
                b["byteLength"].get<uintmax_t>() != size)
              fail(idx("buffers", long(i)) + ": '" + uri + "' has " + std::to_string(size) + " bytes but byteLength is " +
                   std::to_string(b["byteLength"].get<uintmax_t>()));
          }
        }
      } catch (const nlohmann::json::exception&) {
      }
    }
    if (e.find("parse_error") != std::string::npos || e.find("Failed to parse JSON") != std::string::npos ||
        e.find("Root element is not a JSON object") != std::string::npos)
      fail("not a glTF file: invalid JSON: " + e);
    if (e.find("\"asset\" object not found") != std::string::npos)
      fail("not a glTF file: no \"asset\" object with a \"version\"");
    fail("invalid glTF: " + (e.empty() ? std::string("tinygltf gave no reason") : e));
  }

  void check_asset() {
    const std::string& v = model_.asset.version;
    if (v.rfind("2.", 0) != 0) fail("asset.version is '" + v + "': only glTF 2.0 is supported");
    if (!model_.asset.minVersion.empty() && model_.asset.minVersion != "2.0")
      fail("asset.minVersion is '" + model_.asset.minVersion + "': only glTF 2.0 is supported");
    for (size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
      const std::string& ext = model_.extensionsRequired[i];
      if (!supported_extensions().count(ext))
        fail(idx("extensionsRequired", long(i)) + ": extension '" + ext +
             "' is required by the file but not supported (supported: KHR_texture_transform, KHR_lights_punctual, "
             "KHR_materials_emissive_strength)");
    }
    std::string unused;
    for (const std::string& ext : model_.extensionsUsed)
      if (!supported_extensions().count(ext)) unused += (unused.empty() ? "" : ", ") + ext;
    if (!unused.empty()) warn("extensions ignored: " + unused);
  }

  // The nodes to start from, with how the file names them.
  std::vector<std::pair<int, std::string>> root_nodes() {
    std::vector<std::pair<int, std::string>> out;
    int s = options_.scene >= 0 ? options_.scene : model_.defaultScene;
    if (options_.scene >= 0 && size_t(options_.scene) >= model_.scenes.size())
      fail("scene " + std::to_string(options_.scene) + " was asked for but the file has " +
           std::to_string(model_.scenes.size()) + " scenes");
    if (s < 0 && !model_.scenes.empty()) s = 0;
    if (s >= int(model_.scenes.size())) fail("scene: scene " + std::to_string(s) + " does not exist (the file has " + std::to_string(model_.scenes.size()) + " scenes)");
    if (s >= 0) {
      const tinygltf::Scene& sc = model_.scenes[size_t(s)];
      for (size_t k = 0; k < sc.nodes.size(); ++k)
        out.emplace_back(sc.nodes[k], idx("scenes", s) + "." + idx("nodes", long(k)));
      return out;
    }
    // No scenes at all: every node no other node names as a child.
    if (!model_.nodes.empty()) warn("the file has no scenes: drawing every node that has no parent");
    std::vector<uint8_t> is_child(model_.nodes.size(), 0);
    for (const tinygltf::Node& n : model_.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < is_child.size()) is_child[size_t(c)] = 1;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!is_child[i]) out.emplace_back(int(i), idx("nodes", long(i)));
    if (out.empty() && !model_.nodes.empty())
      fail("nodes: every node is some node's child: the node graph is recursive");
    return out;
  }

  // ---- nodes ----------------------------------------------------------------

  mat4 node_matrix(const tinygltf::Node& n, const std::string& where) {
    auto check = [&](const std::vector<double>& v, size_t want, const char* name) {
      if (!v.empty() && v.size() != want)
        fail(where + "." + name + ": expected " + std::to_string(want) + " numbers, found " + std::to_string(v.size()));
      for (double d : v)
        if (!std::isfinite(d)) fail(where + "." + name + ": not a finite number");
    };
    check(n.matrix, 16, "matrix");
    if (!n.matrix.empty()) {
      mat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = float(n.matrix[size_t(4 * c + r)]);  // column-major, as glm
      return m;
    }
    check(n.translation, 3, "translation");
    check(n.rotation, 4, "rotation");
    check(n.scale, 3, "scale");
    mat4 m(1.f);
    if (!n.translation.empty()) m = glm::translate(m, vec3(n.translation[0], n.translation[1], n.translation[2]));
    if (!n.rotation.empty()) {
      glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));  // w, x, y, z
      float len = glm::length(q);
      if (!(len > 0.f)) fail(where + ".rotation: the quaternion is zero");
      m = m * glm::mat4_cast(q / len);
    }
    if (!n.scale.empty()) m = glm::scale(m, vec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
  }

  int add_node(Node n) {
    scene_.nodes.push_back(std::move(n));
    return int(scene_.nodes.size()) - 1;
  }

  // `ref` is how the parent names the node, e.g. "nodes[0].children[2]".
  // `depth` is the node's depth in the Scene (the root group is 1); its mesh
  // primitives become shape nodes one level deeper, within max_node_depth.
  int convert_node(int i, const std::string& ref, const mat4& parent_world, int depth = 2) {
    if (depth + 1 > max_node_depth)
      fail(ref + ": the node hierarchy is too deep (a scene holds at most " + std::to_string(max_node_depth) + " levels)");
    if (i < 0 || size_t(i) >= model_.nodes.size())
      fail(ref + ": node " + std::to_string(i) + " does not exist (the file has " + std::to_string(model_.nodes.size()) +
           " nodes)");
    const std::string where = idx("nodes", i);
    if (on_path_[size_t(i)])
      fail(ref + ": " + where + " is its own ancestor (recursive node graph)");
    if (nodes_[size_t(i)] != invalid) return nodes_[size_t(i)];  // a second parent: share the subtree
    on_path_[size_t(i)] = 1;
    const tinygltf::Node& n = model_.nodes[size_t(i)];
    Node out;
    out.kind = Node::Kind::transform;
    out.name = n.name.empty() ? where : n.name;
    out.local = node_matrix(n, where);
    const mat4 world = parent_world * out.local;

    if (n.mesh != -1) {
      if (n.mesh < 0 || size_t(n.mesh) >= model_.meshes.size())
        fail(where + ".mesh: mesh " + std::to_string(n.mesh) + " does not exist (the file has " +
             std::to_string(model_.meshes.size()) + " meshes)");
      for (const Primitive& p : convert_mesh(n.mesh)) {
        Node shape;
        shape.kind = Node::Kind::shape;
        shape.name = scene_.meshes[size_t(p.mesh)].name;
        shape.shape_kind = ShapeKind::mesh;
        shape.shape = p.mesh;
        shape.material = p.material;
        out.children.push_back(add_node(std::move(shape)));
      }
    }
    if (n.camera != -1) place_camera(n.camera, where, world);
    auto lit = n.extensions.find("KHR_lights_punctual");
    if (lit != n.extensions.end()) {
      const tinygltf::Value& v = lit->second;
      if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber())
        fail(where + ".extensions.KHR_lights_punctual: expected an object with a \"light\" index");
      place_light(v.Get("light").GetNumberAsInt(), where, world);
    }
    for (size_t k = 0; k < n.children.size(); ++k)
      out.children.push_back(convert_node(n.children[k], where + "." + idx("children", long(k)), world, depth + 1));
    on_path_[size_t(i)] = 0;
    int index = add_node(std::move(out));
    nodes_[size_t(i)] = index;
    return index;
  }

  // ---- cameras and lights ------------------------------------------------------

  void place_camera(int c, const std::string& where, const mat4& world) {
    if (c < 0 || size_t(c) >= model_.cameras.size())
      fail(where + ".camera: camera " + std::to_string(c) + " does not exist (the file has " +
           std::to_string(model_.cameras.size()) + " cameras)");
    const tinygltf::Camera& gc = model_.cameras[size_t(c)];
    const std::string cw = idx("cameras", c);
    Camera cam;
    cam.name = gc.name.empty() ? cw : gc.name;
    cam.aspect = Camera::Aspect::fit;  // the image's shape decides; aspectRatio is not enforced
    cam.up_vector = Camera::UpVector::orthonormal;
    // A glTF camera looks down its local -z with +y up.
    cam.center = transform_point(world, vec3(0.f));
    vec3 dir = transform_vector(world, vec3(0.f, 0.f, -1.f));
    vec3 up = transform_vector(world, vec3(0.f, 1.f, 0.f));
    if (!(glm::length(dir) > 0.f) || !(glm::length(glm::cross(dir, up)) > 0.f) || !is_finite(cam.center)) {
      warn(where + ": the camera's transform is degenerate; camera skipped");
      return;
    }
    cam.direction = glm::normalize(dir);
    cam.up = glm::normalize(up);
    if (gc.type == "perspective") {
      double yfov = gc.perspective.yfov;
      if (!(yfov > 0.0 && yfov < kPi)) fail(cw + ".perspective.yfov: " + std::to_string(yfov) + " is not in (0, pi)");
      cam.projection = Camera::Projection::perspective;
      cam.fov_deg = float(yfov * 180.0 / kPi);
    } else if (gc.type == "orthographic") {
      double ymag = gc.orthographic.ymag;
      if (!(std::abs(ymag) > 0.0) || !std::isfinite(ymag)) fail(cw + ".orthographic.ymag: must not be zero");
      cam.projection = Camera::Projection::orthographic;
      cam.ortho_height = float(2.0 * std::abs(ymag));  // ymag is half the view's height
    } else {
      fail(cw + ".type: '" + gc.type + "' is neither perspective nor orthographic");
    }
    scene_.cameras.push_back(cam);
  }

  // KHR_lights_punctual. Units: point and spot intensity is in candela
  // (lm/sr), directional in lux (lm/m^2). The shader's light colour is what
  // a surface facing the light receives: lux for a directional light, and
  // colour / (falloff d^2) for point and spot lights, so with falloff = 1
  // (inverse square) candela / d^2 is lux too. Intensity therefore goes into
  // the colour unscaled: a 1 cd point light 1 m away lights like a 1 lx sun.
  // (Exporters turn watts into candela, e.g. Blender: W / (4 pi) * 683 / 100
  // ... such scenes can be bright; exposure is the renderer's business.)
  void place_light(int li, const std::string& where, const mat4& world) {
    if (li < 0 || size_t(li) >= model_.lights.size())
      fail(where + ".extensions.KHR_lights_punctual.light: light " + std::to_string(li) +
           " does not exist (the file has " + std::to_string(model_.lights.size()) + " lights)");
    const tinygltf::Light& gl = model_.lights[size_t(li)];
    const std::string lw = "extensions.KHR_lights_punctual." + idx("lights", li);
    Light l;
    l.name = gl.name.empty() ? lw : gl.name;
    vec3 color(1.f);
    if (!gl.color.empty()) {
      if (gl.color.size() != 3) fail(lw + ".color: expected 3 numbers, found " + std::to_string(gl.color.size()));
      color = vec3(gl.color[0], gl.color[1], gl.color[2]);
    }
    if (!(gl.intensity >= 0.0) || !std::isfinite(gl.intensity))
      fail(lw + ".intensity: " + std::to_string(gl.intensity) + " is not a finite number >= 0");
    l.color = color * float(gl.intensity);
    l.position = transform_point(world, vec3(0.f));
    vec3 dir = transform_vector(world, vec3(0.f, 0.f, -1.f));  // lights shine down their local -z
    l.direction = glm::length(dir) > 0.f ? glm::normalize(dir) : vec3(0.f, 0.f, -1.f);
    if (gl.type == "directional") {
      l.kind = Light::Kind::directional;
    } else if (gl.type == "point" || gl.type == "spot") {
      l.kind = gl.type == "point" ? Light::Kind::point : Light::Kind::spot;
      l.falloff = 1.f;  // inverse square, see above
      if (gl.range < 0.0 || !std::isfinite(gl.range)) fail(lw + ".range: must be a positive number");
      l.range = float(gl.range);
      if (l.kind == Light::Kind::spot) {
        double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner < outer && outer <= kPi / 2 + 1e-6))
          fail(lw + ".spot: cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2 (found " +
               std::to_string(inner) + ", " + std::to_string(outer) + ")");
        l.spot_inner_deg = float(inner * 180.0 / kPi);
        l.spot_outer_deg = float(outer * 180.0 / kPi);
      }
    } else {
      fail(lw + ".type: '" + gl.type + "' is not directional, point or spot");
    }
    scene_.lights.push_back(l);
  }

  // ---- materials and textures -----------------------------------------------

  // glTF metallic/roughness to the course's Phong (K, Ks, n), a documented
  // approximation (the renderer has no environment to reflect):
  //   K  = baseColorFactor x baseColorTexture texel: the diffuse colour, also
  //        for metals, which would otherwise render black;
  //   Ks = F0 (1 - roughness)^2, F0 = mix(0.04, baseColorFactor.rgb, metallic):
  //        Schlick's reflectance at normal incidence, faded out on rough
  //        surfaces whose (unnormalised) Phong lobe would be a broad glow;
  //   n  = (2 / alpha^2 - 2) / 4, alpha = roughness^2, clamped to [1, 1024]:
  //        the Blinn-Phong exponent of a microfacet lobe of width alpha
  //        (Walter et al. 2007), divided by 4 because the shader's lobe is
  //        (L.R)^n and the angle between L and R is twice that between N and H.
  static void pbr_to_phong(vec3 base, float metallic, float roughness, Material& m) {
    metallic = std::clamp(metallic, 0.f, 1.f);
    roughness = std::clamp(roughness, 0.f, 1.f);
    vec3 f0 = glm::mix(vec3(0.04f), base, metallic);
    float smooth = 1.f - roughness;
    m.specular = f0 * smooth * smooth;
    float alpha2 = roughness * roughness * roughness * roughness;
    float n = alpha2 > 0.f ? (2.f / alpha2 - 2.f) / 4.f : 1024.f;
    m.shininess = std::clamp(n, 1.f, 1024.f);
  }

  struct TextureRef {
    int texture = invalid;  // Scene texture
    int texcoord = 0;       // TEXCOORD_n
    UvTransform transform;
  };

  static std::vector<float> numbers(const tinygltf::Value& v) {
    std::vector<float> out;
    if (!v.IsArray()) return out;
    for (size_t i = 0; i < v.ArrayLen(); ++i) {
      const tinygltf::Value& e = v.Get(int(i));
      out.push_back(e.IsNumber() ? float(e.GetNumberAsDouble()) : std::numeric_limits<float>::quiet_NaN());
    }
    return out;
  }

  TextureRef texture_ref(const tinygltf::TextureInfo& info, const std::string& where) {
    TextureRef r;
    r.texcoord = info.texCoord;
    if (r.texcoord < 0) fail(where + ".texCoord: " + std::to_string(r.texcoord) + " is negative");
    r.texture = texture(info.index, where);
    auto it = info.extensions.find("KHR_texture_transform");
    if (it != info.extensions.end()) {
      const tinygltf::Value& t = it->second;
      const std::string tw = where + ".extensions.KHR_texture_transform";
      if (!t.IsObject()) fail(tw + ": expected an object");
      vec2 offset(0.f), scale(1.f);
      float rotation = 0.f;
      if (t.Has("offset")) {
        std::vector<float> o = numbers(t.Get("offset"));
        if (o.size() != 2 || !std::isfinite(o[0]) || !std::isfinite(o[1])) fail(tw + ".offset: expected 2 numbers");
        offset = vec2(o[0], o[1]);
      }
      if (t.Has("scale")) {
        std::vector<float> s = numbers(t.Get("scale"));
        if (s.size() != 2 || !std::isfinite(s[0]) || !std::isfinite(s[1])) fail(tw + ".scale: expected 2 numbers");
        scale = vec2(s[0], s[1]);
      }
      if (t.Has("rotation")) {
        const tinygltf::Value& rv = t.Get("rotation");
        if (!rv.IsNumber() || !std::isfinite(rv.GetNumberAsDouble())) fail(tw + ".rotation: expected a number");
        rotation = float(rv.GetNumberAsDouble());
      }
      if (t.Has("texCoord")) {
        const tinygltf::Value& tc = t.Get("texCoord");
        if (!tc.IsNumber() || tc.GetNumberAsInt() < 0) fail(tw + ".texCoord: expected an index >= 0");
        r.texcoord = tc.GetNumberAsInt();  // overrides the textureInfo's
      }
      r.transform = gltf_uv_transform_to_scene(offset, rotation, scale);
    }
    return r;
  }

  // Scene texture for glTF texture ti (sRGB colour data), or invalid when its
  // image could not be loaded (warned about).
  int texture(int ti, const std::string& where) {
    if (ti < 0 || size_t(ti) >= model_.textures.size())
      fail(where + ".index: texture " + std::to_string(ti) + " does not exist (the file has " +
           std::to_string(model_.textures.size()) + " textures)");
    if (textures_[size_t(ti)] != -2) return textures_[size_t(ti)];
    textures_[size_t(ti)] = invalid;
    const tinygltf::Texture& t = model_.textures[size_t(ti)];
    const std::string tw = idx("textures", ti);
    if (t.source < 0) {
      warn(tw + ": no image this reader can use (source missing; image extensions are not supported); untextured");
      return invalid;
    }
    if (size_t(t.source) >= model_.images.size())
      fail(tw + ".source: image " + std::to_string(t.source) + " does not exist (the file has " +
           std::to_string(model_.images.size()) + " images)");
    const tinygltf::Image& img = model_.images[size_t(t.source)];
    const std::string iw = idx("images", t.source);
    if (img.image.empty() || img.width <= 0 || img.height <= 0) {
      warn(iw + (img.uri.empty() || is_data_uri(img.uri) ? "" : " ('" + img.uri + "')") +
           ": not loaded; materials using it are untextured");
      return invalid;
    }
    if (img.bits != 8 || img.component < 1 || img.component > 4 ||
        img.image.size() != size_t(img.width) * size_t(img.height) * size_t(img.component)) {
      warn(iw + ": unexpected pixel layout from the image decoder; materials using it are untextured");
      return invalid;
    }
    Texture tex;
    tex.name = !img.name.empty() ? img.name : (!img.uri.empty() && !is_data_uri(img.uri) ? img.uri : iw);
    if (!img.uri.empty() && !is_data_uri(img.uri))
      tex.path = (fs::path(path_).parent_path() / percent_decode(img.uri)).lexically_normal().string();
    tex.width = img.width;
    tex.height = img.height;
    tex.channels = img.component;
    tex.pixels = img.image;
    tex.srgb = true;
    tex.lookup = Texture::Lookup::standard;
    if (t.sampler >= 0) {
      if (size_t(t.sampler) >= model_.samplers.size())
        fail(tw + ".sampler: sampler " + std::to_string(t.sampler) + " does not exist (the file has " +
             std::to_string(model_.samplers.size()) + " samplers)");
      const tinygltf::Sampler& s = model_.samplers[size_t(t.sampler)];
      const std::string sw = idx("samplers", t.sampler);
      tex.wrap_u = wrap(s.wrapS, sw + ".wrapS");
      tex.wrap_v = wrap(s.wrapT, sw + ".wrapT");
      tex.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Texture::Filter::nearest : Texture::Filter::linear;
    } else {
      tex.wrap_u = tex.wrap_v = Texture::Wrap::repeat;  // the specification's default sampler
      tex.filter = Texture::Filter::linear;
    }
    scene_.textures.push_back(std::move(tex));
    textures_[size_t(ti)] = int(scene_.textures.size()) - 1;
    return textures_[size_t(ti)];
  }

  Texture::Wrap wrap(int mode, const std::string& where) {
    switch (mode) {
      case TINYGLTF_TEXTURE_WRAP_REPEAT: return Texture::Wrap::repeat;
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Texture::Wrap::clamp;
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Texture::Wrap::mirror;
    }
    warn(where + ": unknown wrap mode " + std::to_string(mode) + "; using REPEAT");
    return Texture::Wrap::repeat;
  }

  // Scene material for glTF material gi (-1: the specification's default material).
  int material(int gi, const std::string& where) {
    if (gi == -1) {
      if (default_material_ == invalid) {
        Material m;
        m.name = "default";
        m.texture_modulates = true;
        m.double_sided = false;
        pbr_to_phong(vec3(1.f), 1.f, 1.f, m);  // base colour 1, metallic 1, roughness 1
        scene_.materials.push_back(m);
        material_texcoord_.push_back(0);
        default_material_ = int(scene_.materials.size()) - 1;
      }
      return default_material_;
    }
    if (gi < 0 || size_t(gi) >= model_.materials.size())
      fail(where + ": material " + std::to_string(gi) + " does not exist (the file has " +
           std::to_string(model_.materials.size()) + " materials)");
    if (materials_[size_t(gi)] != invalid) return materials_[size_t(gi)];
    const tinygltf::Material& gm = model_.materials[size_t(gi)];
    const std::string mw = idx("materials", gi);
    const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name.empty() ? mw : gm.name;
    m.texture_modulates = true;
    if (pbr.baseColorFactor.size() != 4)
      fail(mw + ".pbrMetallicRoughness.baseColorFactor: expected 4 numbers, found " +
           std::to_string(pbr.baseColorFactor.size()));
    vec4 base(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    if (!is_finite(vec3(base)) || !std::isfinite(base.a))
      fail(mw + ".pbrMetallicRoughness.baseColorFactor: not finite");
    m.diffuse = vec3(base);
    pbr_to_phong(vec3(base), float(pbr.metallicFactor), float(pbr.roughnessFactor), m);
    int texcoord = 0;
    if (pbr.baseColorTexture.index >= 0 || pbr.baseColorTexture.index < -1) {
      TextureRef r = texture_ref(pbr.baseColorTexture, mw + ".pbrMetallicRoughness.baseColorTexture");
      m.diffuse_texture = r.texture;
      texcoord = r.texcoord;
      if (r.texture != invalid) m.uv_transform = r.transform;
    }
    if (gm.emissiveFactor.size() == 3) m.emission = vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
    else if (!gm.emissiveFactor.empty())
      fail(mw + ".emissiveFactor: expected 3 numbers, found " + std::to_string(gm.emissiveFactor.size()));
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end()) {
      const tinygltf::Value& v = it->second;
      if (v.IsObject() && v.Has("emissiveStrength") && v.Get("emissiveStrength").IsNumber())
        m.emission *= float(v.Get("emissiveStrength").GetNumberAsDouble());
    }
    if (!is_finite(m.emission)) fail(mw + ".emissiveFactor: not finite");
    // Cut-outs: the shader compares the texel's alpha with alpha_cutoff, while
    // glTF compares baseColorFactor.a x texel alpha with alphaCutoff; fold the
    // factor into the threshold. (Without a texture a uniform alpha below the
    // cutoff cannot be expressed: such a material stays opaque.)
    auto cutoff_for = [&](float c) { return base.a > 0.f ? c / base.a : 2.f; };
    if (gm.alphaMode == "MASK") {
      m.alpha_cutoff = cutoff_for(float(gm.alphaCutoff));
    } else if (gm.alphaMode == "BLEND") {
      m.alpha_cutoff = cutoff_for(0.5f);
      warn(mw + ": alphaMode BLEND is drawn as MASK with cutoff 0.5 (no blending in this renderer)");
    } else if (gm.alphaMode != "OPAQUE" && !gm.alphaMode.empty()) {
      warn(mw + ": unknown alphaMode '" + gm.alphaMode + "'; drawn OPAQUE");
    }
    m.double_sided = gm.doubleSided;
    m.two_sided_lighting = gm.doubleSided;  // the specification reverses back-face normals
    if (pbr.metallicRoughnessTexture.index >= 0) unused_textures_.insert("metallicRoughnessTexture");
    if (gm.normalTexture.index >= 0) unused_textures_.insert("normalTexture");
    if (gm.occlusionTexture.index >= 0) unused_textures_.insert("occlusionTexture");
    if (gm.emissiveTexture.index >= 0) unused_textures_.insert("emissiveTexture");
    scene_.materials.push_back(std::move(m));
    material_texcoord_.push_back(texcoord);
    materials_[size_t(gi)] = int(scene_.materials.size()) - 1;
    return materials_[size_t(gi)];
  }

  // ---- accessors ----------------------------------------------------------------

  const tinygltf::Accessor& accessor(int a, const std::string& where) {
    if (a < 0 || size_t(a) >= model_.accessors.size())
      fail(where + ": accessor " + std::to_string(a) + " does not exist (the file has " +
           std::to_string(model_.accessors.size()) + " accessors)");
    return model_.accessors[size_t(a)];
  }

  // The bytes of bufferView `v`, checked against its buffer.
  const unsigned char* view_bytes(int v, const std::string& where, size_t* length, size_t* stride) {
    if (v < 0 || size_t(v) >= model_.bufferViews.size())
      fail(where + ": bufferView " + std::to_string(v) + " does not exist (the file has " +
           std::to_string(model_.bufferViews.size()) + " bufferViews)");
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(v)];
    const std::string vw = idx("bufferViews", v);
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
      fail(vw + ".buffer: buffer " + std::to_string(bv.buffer) + " does not exist (the file has " +
           std::to_string(model_.buffers.size()) + " buffers)");
    const tinygltf::Buffer& buf = model_.buffers[size_t(bv.buffer)];
    if (!fits(bv.byteOffset, bv.byteLength, buf.data.size()))
      fail(vw + ": bytes " + std::to_string(bv.byteOffset) + " to " + std::to_string(bv.byteOffset + bv.byteLength) +
           " lie past the end of " + idx("buffers", bv.buffer) + " (" + std::to_string(buf.data.size()) + " bytes)");
    *length = bv.byteLength;
    *stride = bv.byteStride;
    return buf.data.data() + bv.byteOffset;
  }

  // Reads accessor `a` as count x components floats after checking its type
  // against `types` and its component type (FLOAT, or normalised unsigned
  // integers where `normalized_ok`). Applies sparse substitution.
  std::vector<float> read_floats(int a, const std::string& where, std::initializer_list<int> types, bool normalized_ok,
                                 int* components_out, size_t* count_out) {
    const tinygltf::Accessor& acc = accessor(a, where);
    const std::string aw = where + " (" + idx("accessors", a) + ")";
    bool type_ok = std::find(types.begin(), types.end(), acc.type) != types.end();
    bool ct_ok = acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                 (normalized_ok && acc.normalized &&
                  (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                   acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    if (!type_ok || !ct_ok) {
      std::string want;
      for (int t : types) want += std::string(want.empty() ? "" : " or ") + type_name(t);
      want += normalized_ok ? " of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT" : " of FLOAT";
      fail(aw + ": accessor is " + type_name(acc.type) + " of " + component_name(acc.componentType) +
           (acc.normalized ? " (normalized)" : "") + ", expected " + want);
    }
    const int nc = type_components(acc.type);
    std::vector<float> out;
    read_elements(acc, aw, nc, [&](size_t count) { out.assign(count * size_t(nc), 0.f); },
                  [&](size_t i, const unsigned char* p) {
                    const int cs = component_size(acc.componentType);
                    for (int c = 0; c < nc; ++c)
                      out[i * size_t(nc) + size_t(c)] = read_component(p + c * cs, acc.componentType, acc.normalized);
                  });
    *components_out = nc;
    *count_out = acc.count;
    return out;
  }

  std::vector<uint32_t> read_indices(int a, const std::string& where) {
    const tinygltf::Accessor& acc = accessor(a, where);
    const std::string aw = where + " (" + idx("accessors", a) + ")";
    if (acc.type != TINYGLTF_TYPE_SCALAR ||
        (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
      fail(aw + ": accessor is " + type_name(acc.type) + " of " + component_name(acc.componentType) +
           ", expected SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    std::vector<uint32_t> out;
    read_elements(acc, aw, 1, [&](size_t count) { out.assign(count, 0u); },
                  [&](size_t i, const unsigned char* p) { out[i] = read_index(p, acc.componentType); });
    return out;
  }

  // The element walk shared by both readers: bounds of bufferView, stride and
  // buffer checked, then sparse values substituted.
  template <class Alloc, class Put>
  void read_elements(const tinygltf::Accessor& acc, const std::string& aw, int nc, Alloc&& alloc, Put&& put) {
    const int cs = component_size(acc.componentType);
    const size_t elem = size_t(cs) * size_t(nc);
    // Without a bufferView the elements are zeros (sparse may then set some);
    // bound the count so a lying file cannot make us allocate without limit.
    constexpr size_t max_elements = size_t(1) << 28;
    if (acc.count > max_elements) fail(aw + ": count " + std::to_string(acc.count) + " is implausibly large");
    if (acc.bufferView == -1) {
      alloc(acc.count);
    } else {
      size_t length = 0, stride = 0;
      const unsigned char* base = view_bytes(acc.bufferView, aw + ".bufferView", &length, &stride);
      if (stride != 0 && stride < elem)
        fail(aw + ": " + idx("bufferViews", acc.bufferView) + ".byteStride " + std::to_string(stride) +
             " is smaller than one element (" + std::to_string(elem) + " bytes)");
      if (stride == 0) stride = elem;
      if (acc.count > 0) {
        // offset + stride (count - 1) + elem <= length, without overflow
        uint64_t last = uint64_t(stride) * uint64_t(acc.count - 1);
        if (!fits(acc.byteOffset, last, length) || !fits(acc.byteOffset + last, elem, length))
          fail(aw + ": " + std::to_string(acc.count) + " elements of " + std::to_string(elem) + " bytes (stride " +
               std::to_string(stride) + ") from byte " + std::to_string(acc.byteOffset) + " run past the end of " +
               idx("bufferViews", acc.bufferView) + " (" + std::to_string(length) + " bytes)");
      }
      alloc(acc.count);
      for (size_t i = 0; i < acc.count; ++i) put(i, base + acc.byteOffset + i * stride);
    }
    if (!acc.sparse.isSparse) return;
    const std::string sw = aw + ".sparse";
    const int sc = acc.sparse.count;
    if (sc < 1 || size_t(sc) > acc.count)
      fail(sw + ".count: " + std::to_string(sc) + " is not between 1 and the accessor's count " +
           std::to_string(acc.count));
    const int ict = acc.sparse.indices.componentType;
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(sw + ".indices.componentType: " + std::to_string(ict) + " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0) fail(sw + ": negative byteOffset");
    size_t ilen = 0, istride = 0, vlen = 0, vstride = 0;
    const unsigned char* ib = view_bytes(acc.sparse.indices.bufferView, sw + ".indices.bufferView", &ilen, &istride);
    const unsigned char* vb = view_bytes(acc.sparse.values.bufferView, sw + ".values.bufferView", &vlen, &vstride);
    const size_t isize = size_t(component_size(ict));
    if (!fits(size_t(acc.sparse.indices.byteOffset), isize * size_t(sc), ilen))
      fail(sw + ".indices: " + std::to_string(sc) + " indices run past the end of " +
           idx("bufferViews", acc.sparse.indices.bufferView) + " (" + std::to_string(ilen) + " bytes)");
    if (!fits(size_t(acc.sparse.values.byteOffset), elem * size_t(sc), vlen))
      fail(sw + ".values: " + std::to_string(sc) + " values run past the end of " +
           idx("bufferViews", acc.sparse.values.bufferView) + " (" + std::to_string(vlen) + " bytes)");
    ib += acc.sparse.indices.byteOffset;
    vb += acc.sparse.values.byteOffset;
    for (size_t j = 0; j < size_t(sc); ++j) {
      uint32_t target = read_index(ib + j * isize, ict);
      if (target >= acc.count)
        fail(sw + ".indices[" + std::to_string(j) + "]: " + std::to_string(target) + " is past the accessor's " +
             std::to_string(acc.count) + " elements");
      put(target, vb + j * elem);
    }
  }

  // ---- meshes --------------------------------------------------------------------

  const std::vector<Primitive>& convert_mesh(int mi) {
    if (mesh_done_[size_t(mi)]) return meshes_[size_t(mi)];
    mesh_done_[size_t(mi)] = 1;
    const tinygltf::Mesh& gm = model_.meshes[size_t(mi)];
    for (size_t j = 0; j < gm.primitives.size(); ++j) {
      const std::string where = idx("meshes", mi) + "." + idx("primitives", long(j));
      std::string name = gm.name.empty() ? idx("meshes", mi) : gm.name;
      if (gm.primitives.size() > 1) name += "#" + std::to_string(j);
      Primitive p = convert_primitive(gm.primitives[j], where, name);
      if (p.mesh != invalid) meshes_[size_t(mi)].push_back(p);
    }
    return meshes_[size_t(mi)];
  }

  Primitive convert_primitive(const tinygltf::Primitive& prim, const std::string& where, const std::string& name) {
    int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    switch (mode) {
      case TINYGLTF_MODE_TRIANGLES:
      case TINYGLTF_MODE_TRIANGLE_STRIP:
      case TINYGLTF_MODE_TRIANGLE_FAN: break;
      case TINYGLTF_MODE_POINTS:
      case TINYGLTF_MODE_LINE:
      case TINYGLTF_MODE_LINE_LOOP:
      case TINYGLTF_MODE_LINE_STRIP:
        warn(where + ": " + (mode == TINYGLTF_MODE_POINTS ? "points are" : "lines are") + " not rendered; primitive skipped");
        return {};
      default: fail(where + ".mode: " + std::to_string(mode) + " is not a primitive mode (0 to 6)");
    }
    if (!prim.targets.empty()) warn(where + ": morph targets are ignored");
    const int mat = material(prim.material, where + ".material");
    auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end()) {
      warn(where + ": no POSITION attribute; primitive skipped");
      return {};
    }
    Mesh mesh;
    mesh.name = name;
    mesh.source_path = path_;
    int nc = 0;
    size_t nv = 0;
    {
      const std::string aw = where + ".attributes.POSITION";
      std::vector<float> v = read_floats(pos_it->second, aw, {TINYGLTF_TYPE_VEC3}, false, &nc, &nv);
      mesh.positions.resize(nv);
      for (size_t i = 0; i < nv; ++i) {
        mesh.positions[i] = vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        if (!is_finite(mesh.positions[i]))
          fail(aw + ": vertex " + std::to_string(i) + " is not finite (" + std::to_string(v[3 * i]) + ", " +
               std::to_string(v[3 * i + 1]) + ", " + std::to_string(v[3 * i + 2]) + ")");
      }
    }
    auto same_count = [&](size_t n, const std::string& aw) {
      if (n != nv)
        fail(aw + ": " + std::to_string(n) + " elements, but POSITION has " + std::to_string(nv));
    };
    if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
      const std::string aw = where + ".attributes.NORMAL";
      size_t n = 0;
      std::vector<float> v = read_floats(it->second, aw, {TINYGLTF_TYPE_VEC3}, false, &nc, &n);
      same_count(n, aw);
      mesh.normals.resize(nv);
      for (size_t i = 0; i < nv; ++i) {
        vec3 nn(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        float len = glm::length(nn);
        mesh.normals[i] = len > 0.f && std::isfinite(len) ? nn / len : vec3(0.f);
      }
    }
    // Without NORMAL, normals stay empty: the renderer's face normals are the
    // flat normals the specification asks for.
    const int texcoord = material_texcoord_[size_t(mat)];
    const std::string uv_name = "TEXCOORD_" + std::to_string(texcoord);
    if (auto it = prim.attributes.find(uv_name); it != prim.attributes.end()) {
      const std::string aw = where + ".attributes." + uv_name;
      size_t n = 0;
      std::vector<float> v = read_floats(it->second, aw, {TINYGLTF_TYPE_VEC2}, true, &nc, &n);
      same_count(n, aw);
      mesh.uvs.resize(nv);
      for (size_t i = 0; i < nv; ++i) mesh.uvs[i] = vec2(v[2 * i], 1.f - v[2 * i + 1]);  // v = 1 at the top
    } else if (scene_.materials[size_t(mat)].diffuse_texture != invalid) {
      warn(where + ": the material's texture uses " + uv_name + " but the primitive has none; drawn untextured");
    }
    if (auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
      const std::string aw = where + ".attributes.COLOR_0";
      size_t n = 0;
      std::vector<float> v = read_floats(it->second, aw, {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, true, &nc, &n);
      same_count(n, aw);
      mesh.colors.resize(nv);
      for (size_t i = 0; i < nv; ++i)  // linear already; alpha is not used
        mesh.colors[i] = vec3(v[size_t(nc) * i], v[size_t(nc) * i + 1], v[size_t(nc) * i + 2]);
    }

    std::vector<uint32_t> order;
    if (prim.indices != -1) {
      const std::string iw = where + ".indices";
      order = read_indices(prim.indices, iw);
      for (size_t k = 0; k < order.size(); ++k)
        if (order[k] >= nv)
          fail(iw + ": index " + std::to_string(order[k]) + " (element " + std::to_string(k) +
               ") is out of range (the primitive has " + std::to_string(nv) + " vertices)");
    } else {
      order.resize(nv);
      for (size_t i = 0; i < nv; ++i) order[i] = uint32_t(i);
    }
    mesh.indices = triangulate(order, mode, where);
    if (mesh.indices.empty()) {
      warn(where + ": no triangles; primitive skipped");
      return {};
    }
    scene_.meshes.push_back(std::move(mesh));
    return Primitive{int(scene_.meshes.size()) - 1, mat};
  }

  // Triangle lists per the specification's vertex order:
  //   strips: p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}; fans: p_i = {v_{i+1}, v_{i+2}, v_0}.
  // Strip and fan triangles that repeat a vertex (joins) are dropped.
  std::vector<uint32_t> triangulate(const std::vector<uint32_t>& v, int mode, const std::string& where) {
    std::vector<uint32_t> out;
    const size_t n = v.size();
    auto push = [&](uint32_t a, uint32_t b, uint32_t c, bool drop_degenerate) {
      if (drop_degenerate && (a == b || b == c || a == c)) return;
      out.insert(out.end(), {a, b, c});
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (n % 3 != 0)
        warn(where + ": " + std::to_string(n) + " vertices is not a multiple of 3; the last " + std::to_string(n % 3) +
             " are ignored");
      out.reserve(n - n % 3);
      for (size_t i = 0; i + 2 < n; i += 3) push(v[i], v[i + 1], v[i + 2], false);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < n; ++i)
        push(v[i], v[i + 1 + i % 2], v[i + 2 - i % 2], true);
    } else {
      for (size_t i = 0; i + 2 < n; ++i) push(v[i + 1], v[i + 2], v[0], true);
    }
    return out;
  }

  // ---- rayform's own extras (written by gltf_writer.cpp) -----------------------
  // What glTF cannot say (analytic spheres and planes, Phong values, the course
  // camera, ...) travels in "rayform" extras; apply_gltf_rayform_extras
  // (gltf_writer.h) checks each against the file's data and restores it.
  void apply_rayform_extras() {
    GltfSceneMapping map;
    map.scene = options_.scene >= 0 ? options_.scene : std::max(model_.defaultScene, 0);
    map.mesh_primitives.resize(model_.meshes.size());
    for (size_t i = 0; i < model_.meshes.size(); ++i)
      if (mesh_done_[i] && meshes_[i].size() == model_.meshes[i].primitives.size())
        for (const Primitive& p : meshes_[i]) map.mesh_primitives[i].push_back(p.mesh);
    map.materials = materials_;
    map.texture = [this](int ti) { return texture(ti, idx("textures", ti)); };
    std::vector<std::string> extras_warnings;
    apply_gltf_rayform_extras(model_, map, scene_, &extras_warnings);
    for (const std::string& w : extras_warnings) warn(w);
  }

  std::string path_;
  GltfReadOptions options_;
  std::vector<std::string>* warnings_;
  std::set<std::string> seen_warnings_;
  tinygltf::Model model_;
  Scene scene_;
  std::vector<std::vector<Primitive>> meshes_;  // per glTF mesh
  std::vector<uint8_t> mesh_done_;
  std::vector<int> materials_;                  // per glTF material: Scene material
  std::vector<int> material_texcoord_;          // per Scene material: TEXCOORD set of its texture
  std::vector<int> textures_;                   // per glTF texture: Scene texture; -2 not yet converted
  std::vector<int> nodes_;                      // per glTF node: Scene node
  std::vector<uint8_t> on_path_;
  std::set<std::string> unused_textures_;
  int default_material_ = invalid;
};

}  // namespace

Scene read_gltf_scene(const std::string& path, const GltfReadOptions& options, std::vector<std::string>* warnings) {
  return GltfSceneBuilder(path, options, warnings).build();
}

}  // namespace rayform
