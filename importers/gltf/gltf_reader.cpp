#include "gltf/gltf_reader.h"

#include "gltf/gltf_accessors.h"
#include "gltf/gltf_compression.h"
#include "gltf/gltf_extras.h"
#include "gltf/gltf_file_access.h"
#include "gltf/gltf_images.h"
#include "gltf/gltf_material.h"
#include "gltf/gltf_messages.h"
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
#include <numbers>
#include <set>
#include <memory>
#include <sstream>
#include <tuple>

namespace rayform {
namespace fs = std::filesystem;

namespace {

// ---- small helpers ----------------------------------------------------------

std::string idx(const char* array, long i) { return gltf_path(array, i); }

// ---- the reader ---------------------------------------------------------------

// Extensions whose data this reader uses (fully or approximately). Any other
// in extensionsRequired is an error; any other in extensionsUsed is ignored
// and said so.
const std::set<std::string>& supported_extensions() {
  static const std::set<std::string> s = {"KHR_texture_transform",
                                          "KHR_lights_punctual",
                                          "KHR_materials_emissive_strength",
                                          "KHR_draco_mesh_compression",
                                          "EXT_meshopt_compression",
                                          "KHR_mesh_quantization",
                                          "EXT_texture_webp",
                                          "KHR_texture_basisu",
                                          "EXT_mesh_gpu_instancing",
                                          "KHR_materials_ior",
                                          "KHR_materials_specular",
                                          "KHR_materials_unlit",
                                          "KHR_materials_transmission",
                                          "KHR_materials_clearcoat",
                                          "KHR_materials_pbrSpecularGlossiness",
                                          "KHR_materials_sheen",
                                          "KHR_materials_volume",
                                          "KHR_materials_iridescence",
                                          "KHR_materials_anisotropy",
                                          "KHR_materials_dispersion",
                                          "KHR_materials_variants",
                                          "KHR_materials_diffuse_transmission"};
  return s;
}

struct Primitive {
  int mesh = invalid;      // Scene mesh
  int material = invalid;  // Scene material
};

class GltfSceneBuilder {
 public:
  GltfSceneBuilder(const std::string& path, const GltfReadOptions& options, std::vector<std::string>* warnings)
      : path_(path), options_(options), warnings_(warnings), accessors_(model_, path, options.limits.vertices) {}

  Scene build(std::vector<ExtensionUse>* extensions) {
    load();
    check_asset();
    scene_.source_path = path_;
    extras_primitives_.resize(model_.meshes.size());
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
    const std::vector<std::pair<int, std::string>> roots = root_nodes();
    check_node_trees(roots);
    for (const auto& [node, ref] : roots) root.children.push_back(convert_node(node, ref, mat4(1.f)));
    // Skinned meshes, posed in world space (see convert_node).
    root.children.insert(root.children.end(), world_space_shapes_.begin(), world_space_shapes_.end());
    scene_.nodes.push_back(std::move(root));
    scene_.root = int(scene_.nodes.size()) - 1;

    if (!unused_textures_.empty()) {
      std::string list;
      for (const std::string& u : unused_textures_) list += (list.empty() ? "" : ", ") + u;
      warn("materials use " + list + ", which the Phong shader does not use; ignored");
    }
    if (!model_.animations.empty()) warn("animations are ignored: the scene is read in its static pose");
    apply_rayform_extras();
    report_extensions();
    if (extensions) *extensions = std::move(extensions_);
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

    if (glb)
      if (const std::string problem = glb_container_problem(bytes); !problem.empty())
        fail("not a valid binary glTF (GLB): " + problem);
    if (const std::string at = json_too_deep(bytes, glb, options_.limits.json_depth); !at.empty())
      fail(std::string(glb ? "JSON chunk, " : "") + at + ": arrays and objects nest more than " +
           std::to_string(options_.limits.json_depth) + " levels deep (raise the limit with --limit json-depth=N)");
    adapt_json_for_tinygltf(bytes, glb);

    GltfFileAccess fsctx;
    fsctx.base = fs::path(path_).parent_path().string();
    if (fsctx.base.empty()) fsctx.base = ".";
    fsctx.scene_file = path_;
    fsctx.access = options_.access;
    tinygltf::FsCallbacks callbacks = fsctx.callbacks();
    GltfImageContext images;
    images.model = &model_;
    images.decode.max_texels = options_.limits.texture_texels;

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(callbacks);
    loader.SetImageLoader(&gltf_load_image, &images);
    std::string err, warn_text;
    bool ok =
        glb ? loader.LoadBinaryFromMemory(&model_, &err, &warn_text, bytes.data(), unsigned(bytes.size()), fsctx.base)
            : loader.LoadASCIIFromString(&model_, &err, &warn_text, reinterpret_cast<const char*>(bytes.data()),
                                         unsigned(bytes.size()), fsctx.base);
    if (!fsctx.problem.empty()) fail(fsctx.problem);
    if (!ok) diagnose_load_failure(bytes, glb, err);
    for (const std::string& w : images.warnings) warn(w);
    ktx2_images_.insert(images.ktx2_images.begin(), images.ktx2_images.end());
    std::istringstream wl(warn_text);
    std::string l;
    while (std::getline(wl, l)) {
      l = gltf_one_line(l);
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
    std::string e = gltf_one_line(err);
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
          if (bytes.size() >= 20 && len <= bytes.size() - 20)
            json_text.assign(bytes.begin() + 20, bytes.begin() + 20 + len);
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
              fail(idx("buffers", long(i)) + ": '" + uri + "' has " + std::to_string(size) +
                   " bytes but byteLength is " + std::to_string(b["byteLength"].get<uintmax_t>()));
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
             "' is required by the file but not supported (rayform info lists what a file uses; docs/assets.md "
             "what is supported)");
    }
  }

  // The extensions the file names, with how they were used: those recorded
  // while reading keep their entry; the rest of the supported ones were read
  // as they are; unsupported ones are ignored. One warning lists what was
  // approximated or ignored.
  void report_extensions() {
    using Support = ExtensionUse::Support;
    for (const std::string& ext : model_.extensionsUsed) {
      bool seen =
          std::any_of(extensions_.begin(), extensions_.end(), [&](const ExtensionUse& u) { return u.name == ext; });
      if (seen) continue;
      if (supported_extensions().count(ext)) extensions_.push_back({ext, Support::read, ""});
      else extensions_.push_back({ext, Support::ignored, "not supported"});
    }
    std::string approximated, ignored;
    for (const ExtensionUse& u : extensions_) {
      std::string& list = u.support == Support::approximated ? approximated : ignored;
      if (u.support == Support::read) continue;
      list += (list.empty() ? "" : "; ") + u.name + (u.detail.empty() ? "" : " (" + u.detail + ")");
    }
    if (!approximated.empty()) warn("extensions approximated: " + approximated);
    if (!ignored.empty()) warn("extensions ignored: " + ignored);
  }

  void use_extension(const std::string& name, ExtensionUse::Support support = ExtensionUse::Support::read,
                     const std::string& detail = "") {
    for (ExtensionUse& u : extensions_)
      if (u.name == name) return;
    extensions_.push_back({name, support, detail});
  }

  // The nodes to start from, with how the file names them.
  std::vector<std::pair<int, std::string>> root_nodes() {
    std::vector<std::pair<int, std::string>> out;
    int s = options_.scene >= 0 ? options_.scene : model_.defaultScene;
    if (options_.scene >= 0 && size_t(options_.scene) >= model_.scenes.size())
      fail("scene " + std::to_string(options_.scene) + " was asked for but the file has " +
           std::to_string(model_.scenes.size()) + " scenes");
    if (s < 0 && !model_.scenes.empty()) s = 0;
    if (s >= int(model_.scenes.size()))
      fail("scene: scene " + std::to_string(s) + " does not exist (the file has " +
           std::to_string(model_.scenes.size()) + " scenes)");
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

  // A node that is its own ancestor, found by one depth-first pass over the
  // graph from the roots, then from every node (an explicit stack: the graph
  // may be thousands of levels deep; convert_node refuses those).
  void check_no_cycle(const std::vector<std::pair<int, std::string>>& roots) {
    enum : uint8_t { unseen, open, done };
    std::vector<uint8_t> state(model_.nodes.size(), unseen);
    std::vector<std::pair<int, size_t>> stack;  // node, next child to visit
    auto visit = [&](int start) {
      if (start < 0 || size_t(start) >= state.size() || state[size_t(start)] != unseen) return;
      state[size_t(start)] = open;
      stack.emplace_back(start, 0);
      while (!stack.empty()) {
        auto& [node, next] = stack.back();
        const std::vector<int>& children = model_.nodes[size_t(node)].children;
        if (next == children.size()) {
          state[size_t(node)] = done;
          stack.pop_back();
          continue;
        }
        const size_t k = next++;
        const int c = children[k];
        if (c < 0 || size_t(c) >= state.size()) continue;  // convert_node names the bad index
        if (state[size_t(c)] == open)
          fail(idx("nodes", node) + "." + idx("children", long(k)) + ": " + idx("nodes", c) +
               " is its own ancestor (recursive node graph)");
        if (state[size_t(c)] == unseen) {
          state[size_t(c)] = open;
          stack.emplace_back(c, 0);
        }
      }
    };
    for (const auto& root : roots) visit(root.first);
    for (size_t i = 0; i < model_.nodes.size(); ++i) visit(int(i));
  }

  // glTF node hierarchies are disjoint trees (the specification): no node has
  // two parents, and a scene lists root nodes, each once. A file that breaks
  // this is refused: drawing each path through a shared node would multiply
  // the shapes (40 levels of two parents: 2^40 of them).
  void check_node_trees(const std::vector<std::pair<int, std::string>>& roots) {
    check_no_cycle(roots);
    std::vector<int> parent(model_.nodes.size(), invalid);
    for (size_t p = 0; p < model_.nodes.size(); ++p)
      for (int c : model_.nodes[p].children) {
        if (c < 0 || size_t(c) >= parent.size()) continue;  // convert_node names the bad index
        if (parent[size_t(c)] != invalid && parent[size_t(c)] != int(p))
          fail(idx("nodes", c) + ": has two parents, " + idx("nodes", parent[size_t(c)]) + " and " +
               idx("nodes", long(p)) + " (a glTF node hierarchy must be a tree)");
        if (parent[size_t(c)] == int(p)) fail(idx("nodes", long(p)) + ".children: names " + idx("nodes", c) + " twice");
        parent[size_t(c)] = int(p);
      }
    std::vector<uint8_t> listed(model_.nodes.size(), 0);
    for (const auto& [node, ref] : roots) {
      if (node < 0 || size_t(node) >= parent.size()) continue;
      if (parent[size_t(node)] != invalid)
        fail(ref + ": " + idx("nodes", node) + " is a child of " + idx("nodes", parent[size_t(node)]) +
             " (a scene lists root nodes only)");
      if (listed[size_t(node)]++) fail(ref + ": " + idx("nodes", node) + " is listed twice");
    }
  }

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
      glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                  float(n.rotation[2]));  // w, x, y, z
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
      fail(ref + ": the node hierarchy is too deep (a scene holds at most " + std::to_string(max_node_depth) +
           " levels)");
    if (i < 0 || size_t(i) >= model_.nodes.size())
      fail(ref + ": node " + std::to_string(i) + " does not exist (the file has " +
           std::to_string(model_.nodes.size()) + " nodes)");
    const std::string where = idx("nodes", i);
    if (on_path_[size_t(i)]) fail(ref + ": " + where + " is its own ancestor (recursive node graph)");
    if (nodes_[size_t(i)] != invalid) fail(ref + ": " + where + " is reached twice");  // check_node_trees refused it
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
      const tinygltf::Mesh& gm = model_.meshes[size_t(n.mesh)];
      // Morph weights: the node's, else the mesh's, else 0.
      std::vector<float> weights;
      for (double w : n.weights.empty() ? gm.weights : n.weights) {
        if (!std::isfinite(w))
          fail(where + (n.weights.empty() ? idx(".meshes", n.mesh) : std::string()) + ".weights: not finite");
        weights.push_back(float(w));
      }
      if (std::all_of(weights.begin(), weights.end(), [](float w) { return w == 0.f; })) weights.clear();
      if (n.skin != -1) {
        // A skinned mesh is posed by its joints alone, in world space; the
        // node's own transform does not apply to it (the specification).
        const std::vector<int>& shapes = mesh_shapes(n.mesh, weights, i);
        world_space_shapes_.insert(world_space_shapes_.end(), shapes.begin(), shapes.end());
      } else if (auto inst = n.extensions.find("EXT_mesh_gpu_instancing"); inst != n.extensions.end()) {
        for (const mat4& m : instance_matrices(inst->second, where + ".extensions.EXT_mesh_gpu_instancing")) {
          Node copy;
          copy.kind = Node::Kind::transform;
          copy.local = m;
          copy.children = mesh_shapes(n.mesh, weights, invalid);  // one mesh, shared by every instance
          out.children.push_back(add_node(std::move(copy)));
        }
        use_extension("EXT_mesh_gpu_instancing");
      } else {
        const std::vector<int>& shapes = mesh_shapes(n.mesh, weights, invalid);
        out.children.insert(out.children.end(), shapes.begin(), shapes.end());
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

  // EXT_mesh_gpu_instancing: one matrix T R S per instance (each of the three
  // optional), applied before the node's transform.
  std::vector<mat4> instance_matrices(const tinygltf::Value& e, const std::string& ew) {
    if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject())
      fail(ew + ": expected an object with \"attributes\"");
    const tinygltf::Value& attributes = e.Get("attributes");
    struct Attr {
      const char* name;
      int type;
      uint32_t formats;
      GltfAccessors::Floats values;
      bool present = false;
    };
    Attr attrs[] = {{"TRANSLATION", TINYGLTF_TYPE_VEC3, format_float, {}},
                    {"ROTATION", TINYGLTF_TYPE_VEC4, formats_rotation, {}},
                    {"SCALE", TINYGLTF_TYPE_VEC3, format_float, {}}};
    size_t count = 0;
    const char* first = nullptr;
    for (Attr& a : attrs) {
      if (!attributes.Has(a.name)) continue;
      const std::string aw = ew + ".attributes." + a.name;
      const tinygltf::Value& index = attributes.Get(a.name);
      if (!index.IsNumber()) fail(aw + ": expected an accessor index");
      a.values = accessors_.read_floats(index.GetNumberAsInt(), aw, {a.type}, a.formats);
      a.present = true;
      for (float v : a.values.values)
        if (!std::isfinite(v)) fail(aw + ": a value is not finite");
      if (first && a.values.count != count)
        fail(aw + ": " + std::to_string(a.values.count) + " instances, but " + first + " has " + std::to_string(count));
      count = a.values.count;
      first = a.name;
    }
    if (!first) fail(ew + ".attributes: expected TRANSLATION, ROTATION or SCALE");
    std::vector<mat4> out(count, mat4(1.f));
    for (size_t i = 0; i < count; ++i) {
      mat4& m = out[i];
      if (attrs[0].present)
        m = glm::translate(m, vec3(attrs[0].values.values[3 * i], attrs[0].values.values[3 * i + 1],
                                   attrs[0].values.values[3 * i + 2]));
      if (attrs[1].present) {
        const float* q = &attrs[1].values.values[4 * i];
        glm::quat r(q[3], q[0], q[1], q[2]);  // w, x, y, z
        const float len = glm::length(r);
        if (!(len > 0.f)) fail(ew + ".attributes.ROTATION: instance " + std::to_string(i) + "'s quaternion is zero");
        m = m * glm::mat4_cast(r / len);
      }
      if (attrs[2].present)
        m = glm::scale(m, vec3(attrs[2].values.values[3 * i], attrs[2].values.values[3 * i + 1],
                               attrs[2].values.values[3 * i + 2]));
    }
    return out;
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
      if (!(yfov > 0.0 && yfov < std::numbers::pi))
        fail(cw + ".perspective.yfov: " + std::to_string(yfov) + " is not in (0, pi)");
      cam.projection = Camera::Projection::perspective;
      cam.fov_deg = float(yfov * 180.0 / std::numbers::pi);
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
        if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2 + 1e-6))
          fail(lw + ".spot: cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2 (found " +
               std::to_string(inner) + ", " + std::to_string(outer) + ")");
        l.spot_inner_deg = float(inner * 180.0 / std::numbers::pi);
        l.spot_outer_deg = float(outer * 180.0 / std::numbers::pi);
      }
    } else {
      fail(lw + ".type: '" + gl.type + "' is not directional, point or spot");
    }
    scene_.lights.push_back(l);
  }

  // ---- materials and textures -----------------------------------------------

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
    const int source = texture_source(t, tw);
    if (source < 0) {
      warn(tw + ": no image this reader can use (source missing); untextured");
      return invalid;
    }
    const tinygltf::Image& img = model_.images[size_t(source)];
    const std::string iw = idx("images", source);
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

  // The image texture `t` (named `tw`) is drawn with: EXT_texture_webp's
  // source when it decoded, else the core `source`; KHR_texture_basisu's
  // KTX2 image cannot be decoded, so its core `source` stands in for it, and
  // without one the texture is an error. -1: no source at all.
  int texture_source(const tinygltf::Texture& t, const std::string& tw) {
    auto image_index = [&](int i, const std::string& where) {
      if (i < 0 || size_t(i) >= model_.images.size())
        fail(where + ": image " + std::to_string(i) + " does not exist (the file has " +
             std::to_string(model_.images.size()) + " images)");
      return i;
    };
    auto extension_source = [&](const char* name) -> int {
      auto it = t.extensions.find(name);
      if (it == t.extensions.end()) return -2;
      const std::string ew = tw + ".extensions." + name;
      if (!it->second.IsObject() || !it->second.Has("source") || !it->second.Get("source").IsNumber())
        fail(ew + ": expected an object with a \"source\" image index");
      return image_index(it->second.Get("source").GetNumberAsInt(), ew + ".source");
    };
    if (t.source >= 0) image_index(t.source, tw + ".source");
    const int webp = extension_source("EXT_texture_webp");
    if (webp >= 0) {
      if (!model_.images[size_t(webp)].image.empty()) {
        use_extension("EXT_texture_webp");
        return webp;
      }
      if (t.source < 0)
        fail(tw + ".extensions.EXT_texture_webp: " + idx("images", webp) +
             " does not decode as WebP and the texture has no PNG/JPEG fallback source");
    }
    const int basisu = extension_source("KHR_texture_basisu");
    if (basisu >= 0 || (t.source >= 0 && ktx2_images_.count(t.source))) {
      if (t.source < 0 || ktx2_images_.count(t.source))
        fail(tw + (basisu >= 0 ? ".extensions.KHR_texture_basisu" : ".source") +
             ": KTX2 / Basis Universal images cannot be decoded (no decoder is available) and the texture has no "
             "PNG/JPEG fallback source");
      use_extension("KHR_texture_basisu", ExtensionUse::Support::approximated,
                    "KTX2 images not decoded: their PNG/JPEG fallback sources are drawn");
    }
    return t.source;
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
        pbr_to_phong(vec3(1.f), 1.f, 1.f, vec3(gltf_dielectric_f0), m);  // base colour 1, metallic 1, roughness 1
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
    gltf_material_to_phong(gm, path_, mw, m, extensions_);
    const float base_alpha = float(pbr.baseColorFactor[3]);
    int texcoord = 0;
    if (pbr.baseColorTexture.index >= 0 || pbr.baseColorTexture.index < -1) {
      TextureRef r = texture_ref(pbr.baseColorTexture, mw + ".pbrMetallicRoughness.baseColorTexture");
      m.diffuse_texture = r.texture;
      texcoord = r.texcoord;
      if (r.texture != invalid) m.uv_transform = r.transform;
    }
    // The older specular-glossiness workflow's diffuse texture plays the base colour's part.
    if (auto sg = gm.extensions.find("KHR_materials_pbrSpecularGlossiness"); sg != gm.extensions.end()) {
      const std::string sw = mw + ".extensions.KHR_materials_pbrSpecularGlossiness.diffuseTexture";
      if (sg->second.IsObject() && sg->second.Has("diffuseTexture")) {
        const tinygltf::Value& dt = sg->second.Get("diffuseTexture");
        if (!dt.IsObject() || !dt.Has("index") || !dt.Get("index").IsNumber())
          fail(sw + ": expected an object with an \"index\"");
        tinygltf::TextureInfo info;
        info.index = dt.Get("index").GetNumberAsInt();
        if (dt.Has("texCoord") && dt.Get("texCoord").IsNumber()) info.texCoord = dt.Get("texCoord").GetNumberAsInt();
        TextureRef r = texture_ref(info, sw);
        m.diffuse_texture = r.texture;
        texcoord = r.texcoord;
      }
    }
    // Cut-outs: the shader compares the texel's alpha with alpha_cutoff, while
    // glTF compares baseColorFactor.a x texel alpha with alphaCutoff; fold the
    // factor into the threshold. (Without a texture a uniform alpha below the
    // cutoff cannot be expressed: such a material stays opaque.)
    auto cutoff_for = [&](float c) { return base_alpha > 0.f ? c / base_alpha : 2.f; };
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

  // ---- meshes --------------------------------------------------------------------

  // A Draco-compressed primitive, decoded: attribute name -> index into mesh.attributes.
  struct DracoPrimitive {
    DracoMesh mesh;
    std::map<std::string, int> slots;
    int indices = -1;  // the primitive's index accessor (adapt_json_for_tinygltf moved it)
  };

  // KHR_draco_mesh_compression of `prim`, decoded; nullptr when it has none.
  std::unique_ptr<DracoPrimitive> decode_draco_primitive(const tinygltf::Primitive& prim, const std::string& where) {
    auto it = prim.extensions.find("KHR_draco_mesh_compression");
    if (it == prim.extensions.end()) return nullptr;
    const std::string dw = where + ".extensions.KHR_draco_mesh_compression";
    const tinygltf::Value& e = it->second;
    if (!e.IsObject() || !e.Has("bufferView") || !e.Get("bufferView").IsNumber() || !e.Has("attributes") ||
        !e.Get("attributes").IsObject())
      fail(dw + ": expected an object with a \"bufferView\" and \"attributes\"");
    const GltfAccessors::View bytes = accessors_.view(e.Get("bufferView").GetNumberAsInt(), dw + ".bufferView");
    auto out = std::make_unique<DracoPrimitive>();
    std::vector<int> ids;
    const tinygltf::Value& attributes = e.Get("attributes");
    for (const std::string& name : attributes.Keys()) {
      const tinygltf::Value& id = attributes.Get(name);
      if (!id.IsNumber() || id.GetNumberAsInt() < 0)
        fail(dw + ".attributes." + name + ": expected a Draco attribute id");
      if (!prim.attributes.count(name))
        fail(dw + ".attributes." + name + ": the primitive has no accessor for this attribute");
      out->slots[name] = int(ids.size());
      ids.push_back(id.GetNumberAsInt());
    }
    if (e.Has(draco_indices_key) && e.Get(draco_indices_key).IsNumber())
      out->indices = e.Get(draco_indices_key).GetNumberAsInt();
    out->mesh = decode_draco(bytes.data, bytes.length, ids, path_ + ": " + dw);
    use_extension("KHR_draco_mesh_compression");
    return out;
  }

  // Attribute `name` of `prim` as floats: from the Draco mesh when it holds
  // the attribute, else from its accessor. Types and formats checked on the
  // accessor either way.
  GltfAccessors::Floats attribute(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& name,
                                  const std::string& where, std::initializer_list<int> types, uint32_t formats) {
    const int a = prim.attributes.at(name);
    const std::string aw = where + ".attributes." + name;
    if (!draco || !draco->slots.count(name)) return accessors_.read_floats(a, aw, types, formats);
    const tinygltf::Accessor& acc = accessors_.check_format(a, aw, types, formats);
    const DracoAttribute& d = draco->mesh.attributes[size_t(draco->slots.at(name))];
    GltfAccessors::Floats f;
    f.components = gltf_type_components(acc.type);
    f.count = draco->mesh.vertex_count;
    if (d.components != f.components)
      fail(aw + ": the Draco attribute has " + std::to_string(d.components) + " components, the accessor " +
           std::to_string(f.components));
    if (acc.count != f.count)
      fail(aw + " (" + idx("accessors", a) + "): the Draco stream decodes to " + std::to_string(f.count) +
           " vertices but the accessor's count is " + std::to_string(acc.count));
    f.values = d.values;
    if (acc.normalized)
      for (float& v : f.values) v = gltf_normalize_integer(v, acc.componentType);
    return f;
  }

  // How node `skinned_node` poses its skin: per joint, world(joint) x inverseBindMatrix.
  std::vector<mat4> skin_joint_matrices(int skinned_node) {
    const tinygltf::Node& n = model_.nodes[size_t(skinned_node)];
    const std::string sw = idx("skins", n.skin);
    if (n.skin < 0 || size_t(n.skin) >= model_.skins.size())
      fail(idx("nodes", skinned_node) + ".skin: skin " + std::to_string(n.skin) + " does not exist (the file has " +
           std::to_string(model_.skins.size()) + " skins)");
    const tinygltf::Skin& skin = model_.skins[size_t(n.skin)];
    std::vector<mat4> inverse_bind(skin.joints.size(), mat4(1.f));
    if (skin.inverseBindMatrices >= 0) {
      GltfAccessors::Floats ibm = accessors_.read_floats(skin.inverseBindMatrices, sw + ".inverseBindMatrices",
                                                         {TINYGLTF_TYPE_MAT4}, format_float);
      if (ibm.count < skin.joints.size())
        fail(sw + ".inverseBindMatrices: " + std::to_string(ibm.count) + " matrices for " +
             std::to_string(skin.joints.size()) + " joints");
      for (size_t j = 0; j < skin.joints.size(); ++j)
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) inverse_bind[j][c][r] = ibm.values[16 * j + size_t(4 * c + r)];
    }
    std::vector<mat4> out(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int joint = skin.joints[j];
      if (joint < 0 || size_t(joint) >= model_.nodes.size())
        fail(sw + ".joints[" + std::to_string(j) + "]: node " + std::to_string(joint) + " does not exist");
      out[j] = node_world(joint) * inverse_bind[j];
      if (!is_finite(vec3(out[j][0])) || !is_finite(vec3(out[j][1])) || !is_finite(vec3(out[j][2])) ||
          !is_finite(vec3(out[j][3])))
        fail(sw + ".joints[" + std::to_string(j) + "]: the joint's matrix is not finite");
    }
    return out;
  }

  // Node i's world matrix through its (first) parents, whether or not it is in
  // the scene read; joints of skins need it.
  mat4 node_world(int i) {
    if (parents_.empty()) {
      parents_.assign(model_.nodes.size(), invalid);
      for (size_t p = 0; p < model_.nodes.size(); ++p)
        for (int c : model_.nodes[p].children)
          if (c >= 0 && size_t(c) < parents_.size() && parents_[size_t(c)] == invalid) parents_[size_t(c)] = int(p);
    }
    mat4 world(1.f);
    int depth = 0;
    for (int k = i; k != invalid; k = parents_[size_t(k)]) {
      if (++depth > max_node_depth)
        fail(idx("nodes", i) + ": its chain of parents is longer than " + std::to_string(max_node_depth) +
             " (recursive node graph?)");
      world = node_matrix(model_.nodes[size_t(k)], idx("nodes", k)) * world;
    }
    return world;
  }

  // The Scene meshes of glTF mesh `mi` at morph `weights`, posed by the skin
  // of node `skinned_node` (invalid: not skinned), as shape nodes; converted
  // once per combination.
  const std::vector<int>& mesh_shapes(int mi, const std::vector<float>& weights, int skinned_node) {
    MeshKey key{mi, skinned_node, weights};
    auto it = mesh_shapes_.find(key);
    if (it != mesh_shapes_.end()) return it->second;
    const tinygltf::Mesh& gm = model_.meshes[size_t(mi)];
    std::vector<mat4> joints;
    if (skinned_node != invalid) joints = skin_joint_matrices(skinned_node);
    std::vector<int> shapes, meshes;
    for (size_t j = 0; j < gm.primitives.size(); ++j) {
      const std::string where = idx("meshes", mi) + "." + idx("primitives", long(j));
      std::string name = gm.name.empty() ? idx("meshes", mi) : gm.name;
      if (gm.primitives.size() > 1) name += "#" + std::to_string(j);
      Primitive p =
          convert_primitive(gm.primitives[j], where, name, weights, skinned_node != invalid ? &joints : nullptr);
      if (p.mesh == invalid) continue;
      meshes.push_back(p.mesh);
      Node shape;
      shape.kind = Node::Kind::shape;
      shape.name = scene_.meshes[size_t(p.mesh)].name;
      shape.shape_kind = ShapeKind::mesh;
      shape.shape = p.mesh;
      shape.material = p.material;
      shapes.push_back(add_node(std::move(shape)));
    }
    // The extras of a primitive describe its first, unposed conversion.
    if (extras_primitives_[size_t(mi)].empty() && meshes.size() == gm.primitives.size() && skinned_node == invalid)
      extras_primitives_[size_t(mi)] = meshes;
    return mesh_shapes_.emplace(std::move(key), std::move(shapes)).first->second;
  }

  Primitive convert_primitive(const tinygltf::Primitive& prim, const std::string& where, const std::string& name,
                              const std::vector<float>& weights, const std::vector<mat4>* joints) {
    int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    switch (mode) {
      case TINYGLTF_MODE_TRIANGLES:
      case TINYGLTF_MODE_TRIANGLE_STRIP:
      case TINYGLTF_MODE_TRIANGLE_FAN: break;
      case TINYGLTF_MODE_POINTS:
      case TINYGLTF_MODE_LINE:
      case TINYGLTF_MODE_LINE_LOOP:
      case TINYGLTF_MODE_LINE_STRIP:
        warn(where + ": " + (mode == TINYGLTF_MODE_POINTS ? "points are" : "lines are") +
             " not rendered; primitive skipped");
        return {};
      default: fail(where + ".mode: " + std::to_string(mode) + " is not a primitive mode (0 to 6)");
    }
    const int mat = material(prim.material, where + ".material");
    if (!prim.attributes.count("POSITION")) {
      warn(where + ": no POSITION attribute; primitive skipped");
      return {};
    }
    const std::unique_ptr<DracoPrimitive> draco = decode_draco_primitive(prim, where);
    Mesh mesh;
    mesh.name = name;
    mesh.source_path = path_;
    const GltfAccessors::Floats positions =
        attribute(prim, draco.get(), "POSITION", where, {TINYGLTF_TYPE_VEC3}, formats_position);
    const size_t nv = positions.count;
    mesh.positions.resize(nv);
    for (size_t i = 0; i < nv; ++i)
      mesh.positions[i] = vec3(positions.values[3 * i], positions.values[3 * i + 1], positions.values[3 * i + 2]);
    auto same_count = [&](size_t n, const std::string& aw) {
      if (n != nv) fail(aw + ": " + std::to_string(n) + " elements, but POSITION has " + std::to_string(nv));
    };
    auto read_vec3s = [&](const GltfAccessors::Floats& f, std::vector<vec3>& out) {
      out.resize(nv);
      const size_t nc = size_t(f.components);
      for (size_t i = 0; i < nv; ++i) out[i] = vec3(f.values[nc * i], f.values[nc * i + 1], f.values[nc * i + 2]);
    };
    if (prim.attributes.count("NORMAL")) {
      GltfAccessors::Floats f = attribute(prim, draco.get(), "NORMAL", where, {TINYGLTF_TYPE_VEC3}, formats_normal);
      same_count(f.count, where + ".attributes.NORMAL");
      read_vec3s(f, mesh.normals);
    }
    apply_morph_targets(prim, where, weights, mesh);
    if (joints) apply_skin(prim, draco.get(), where, *joints, mesh);
    for (size_t i = 0; i < nv; ++i)
      if (!is_finite(mesh.positions[i])) {
        const vec3& p = mesh.positions[i];
        fail(where + ".attributes.POSITION: vertex " + std::to_string(i) + " is not finite (" + std::to_string(p.x) +
             ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
      }
    for (vec3& n : mesh.normals) {
      const float len = glm::length(n);
      n = len > 0.f && std::isfinite(len) ? n / len : vec3(0.f);
    }
    // Without NORMAL, normals stay empty: the renderer's face normals are the
    // flat normals the specification asks for.
    const int texcoord = material_texcoord_[size_t(mat)];
    const std::string uv_name = "TEXCOORD_" + std::to_string(texcoord);
    if (prim.attributes.count(uv_name)) {
      GltfAccessors::Floats f = attribute(prim, draco.get(), uv_name, where, {TINYGLTF_TYPE_VEC2}, formats_texcoord);
      same_count(f.count, where + ".attributes." + uv_name);
      mesh.uvs.resize(nv);
      for (size_t i = 0; i < nv; ++i)
        mesh.uvs[i] = vec2(f.values[2 * i], 1.f - f.values[2 * i + 1]);  // v = 1 at the top
    } else if (scene_.materials[size_t(mat)].diffuse_texture != invalid) {
      warn(where + ": the material's texture uses " + uv_name + " but the primitive has none; drawn untextured");
    }
    if (prim.attributes.count("COLOR_0")) {
      GltfAccessors::Floats f =
          attribute(prim, draco.get(), "COLOR_0", where, {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, formats_color);
      same_count(f.count, where + ".attributes.COLOR_0");
      read_vec3s(f, mesh.colors);  // linear already; alpha is not used
    }

    std::vector<uint32_t> order;
    const std::string iw = where + ".indices";
    if (draco) {
      order = draco->mesh.indices;
      const int indices = prim.indices != -1 ? prim.indices : draco->indices;
      if (indices != -1 && accessors_.accessor(indices, iw).count != order.size())
        fail(iw + " (" + idx("accessors", indices) + "): the Draco stream decodes to " + std::to_string(order.size()) +
             " indices but the accessor's count is " + std::to_string(accessors_.accessor(indices, iw).count));
    } else if (prim.indices != -1) {
      order = accessors_.read_indices(prim.indices, iw);
    } else {
      order.resize(nv);
      for (size_t i = 0; i < nv; ++i) order[i] = uint32_t(i);
    }
    for (size_t k = 0; k < order.size(); ++k)
      if (order[k] >= nv)
        fail(iw + ": index " + std::to_string(order[k]) + " (element " + std::to_string(k) +
             ") is out of range (the primitive has " + std::to_string(nv) + " vertices)");
    mesh.indices = triangulate(order, mode, where);
    if (mesh.indices.empty()) {
      warn(where + ": no triangles; primitive skipped");
      return {};
    }
    scene_.meshes.push_back(std::move(mesh));
    return Primitive{int(scene_.meshes.size()) - 1, mat};
  }

  // Morph targets at `weights`: POSITION and NORMAL displaced by the
  // weighted sum of the targets' deltas (other target attributes are not used).
  void apply_morph_targets(const tinygltf::Primitive& prim, const std::string& where, const std::vector<float>& weights,
                           Mesh& mesh) {
    const size_t nv = mesh.positions.size();
    for (size_t t = 0; t < prim.targets.size(); ++t) {
      const float w = t < weights.size() ? weights[t] : 0.f;
      if (w == 0.f) continue;
      const std::string tw = where + "." + idx("targets", long(t));
      for (const char* name : {"POSITION", "NORMAL"}) {
        auto it = prim.targets[t].find(name);
        if (it == prim.targets[t].end()) continue;
        std::vector<vec3>& values = std::string(name) == "POSITION" ? mesh.positions : mesh.normals;
        if (values.empty()) continue;  // a NORMAL delta without normals
        const std::string aw = tw + "." + name;
        GltfAccessors::Floats d = accessors_.read_floats(it->second, aw, {TINYGLTF_TYPE_VEC3}, formats_morph_delta);
        if (d.count != nv)
          fail(aw + ": " + std::to_string(d.count) + " elements, but POSITION has " + std::to_string(nv));
        for (size_t i = 0; i < nv; ++i)
          values[i] += w * vec3(d.values[3 * i], d.values[3 * i + 1], d.values[3 * i + 2]);
      }
    }
  }

  // Linear blend skinning into world space: p' = sum_k w_k J_{j_k} p over
  // the sets JOINTS_n / WEIGHTS_n (weights renormalised to sum 1); normals by
  // the blended matrix's linear part (renormalised later).
  void apply_skin(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& where,
                  const std::vector<mat4>& joints, Mesh& mesh) {
    const size_t nv = mesh.positions.size();
    std::vector<mat4> blend(nv, mat4(0.f));
    std::vector<float> total(nv, 0.f);
    for (int set = 0;; ++set) {
      const std::string jn = "JOINTS_" + std::to_string(set), wn = "WEIGHTS_" + std::to_string(set);
      if (!prim.attributes.count(jn) || !prim.attributes.count(wn)) break;
      GltfAccessors::Floats j = attribute(prim, draco, jn, where, {TINYGLTF_TYPE_VEC4}, formats_joints);
      GltfAccessors::Floats w = attribute(prim, draco, wn, where, {TINYGLTF_TYPE_VEC4}, formats_weights);
      if (j.count != nv || w.count != nv)
        fail(where + ".attributes." + jn + ": " + std::to_string(std::min(j.count, w.count)) +
             " elements, but POSITION has " + std::to_string(nv));
      for (size_t i = 0; i < nv; ++i)
        for (size_t k = 0; k < 4; ++k) {
          const float weight = w.values[4 * i + k];
          if (weight == 0.f) continue;
          const size_t joint = size_t(j.values[4 * i + k]);
          if (joint >= joints.size())
            fail(where + ".attributes." + jn + ": vertex " + std::to_string(i) + " names joint " +
                 std::to_string(joint) + " but the skin has " + std::to_string(joints.size()));
          blend[i] += weight * joints[joint];
          total[i] += weight;
        }
    }
    for (size_t i = 0; i < nv; ++i) {
      if (!(total[i] > 0.f)) continue;  // no influence: left in place
      const mat4 m = blend[i] / total[i];
      mesh.positions[i] = transform_point(m, mesh.positions[i]);
      if (!mesh.normals.empty()) mesh.normals[i] = glm::transpose(glm::inverse(mat3(m))) * mesh.normals[i];
    }
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
      for (size_t i = 0; i + 2 < n; ++i) push(v[i], v[i + 1 + i % 2], v[i + 2 - i % 2], true);
    } else {
      for (size_t i = 0; i + 2 < n; ++i) push(v[i + 1], v[i + 2], v[0], true);
    }
    return out;
  }

  // ---- rayform's own extras (written by gltf_writer.cpp) -----------------------
  // What glTF cannot say (analytic spheres and planes, Phong values, the course
  // camera, ...) travels in "rayform" extras; apply_gltf_rayform_extras
  // (gltf_extras.h) checks each against the file's data and restores it.
  void apply_rayform_extras() {
    GltfSceneMapping map;
    map.scene = options_.scene >= 0 ? options_.scene : std::max(model_.defaultScene, 0);
    map.mesh_primitives = extras_primitives_;
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
  GltfAccessors accessors_;  // reads model_'s accessors
  Scene scene_;
  // Shape nodes per (glTF mesh, skinned node or invalid, morph weights).
  using MeshKey = std::tuple<int, int, std::vector<float>>;
  std::map<MeshKey, std::vector<int>> mesh_shapes_;
  std::vector<std::vector<int>> extras_primitives_;  // per glTF mesh: its first conversion's Scene meshes
  std::vector<int> world_space_shapes_;              // shape nodes of skinned meshes (posed in world space)
  std::vector<int> parents_;                         // per glTF node: its first parent (node_world)
  std::set<int> ktx2_images_;                        // images that are KTX2 (not decoded)
  std::vector<ExtensionUse> extensions_;
  std::vector<int> materials_;          // per glTF material: Scene material
  std::vector<int> material_texcoord_;  // per Scene material: TEXCOORD set of its texture
  std::vector<int> textures_;           // per glTF texture: Scene texture; -2 not yet converted
  std::vector<int> nodes_;              // per glTF node: Scene node
  std::vector<uint8_t> on_path_;
  std::set<std::string> unused_textures_;
  int default_material_ = invalid;
};

}  // namespace

Scene read_gltf_scene(const std::string& path, const GltfReadOptions& options, std::vector<std::string>* warnings,
                      std::vector<ExtensionUse>* extensions) {
  return GltfSceneBuilder(path, options, warnings).build(extensions);
}

}  // namespace rayform
