#include "rayform/importers/obj/obj_writer.h"

#include "rayform/importers/material_approximation.h"
#include "rayform/importers/obj/obj_pbr_material.h"
#include "rayform/importers/writer_context.h"
#include "rayform/importers/scene_writer.h"
#include "rayform/base/error.h"
#include "rayform/importers/scene_flatten.h"
#include "rayform/importers/shape_tessellation.h"
#include "rayform/importers/text_format.h"
#include "rayform/importers/texture_files.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

namespace rayform {
namespace fs = std::filesystem;
namespace {

// Exact-value keys for deduplication.
template <size_t N>
std::array<uint32_t, N> bits(const float* f) {
  std::array<uint32_t, N> k;
  std::memcpy(k.data(), f, N * 4);
  return k;
}

class ObjWriter {
 public:
  ObjWriter(const Scene& scene, const std::string& path, const ObjWriteOptions& options,
            std::vector<std::string>* messages)
      : scene_(scene), options_(options), context_(scene, path, options.side_folder, messages) {
    extent_ = scene_extent(scene);
    for (const Mesh& m : scene.meshes) any_colors_ |= !m.colors.empty();
    // Kd/Ks/Ns of every material (metallic-roughness ones approximated).
    // Kd is the base colour for MTL's PBR statements (obj_pbr_material.h),
    // also where the Phong approximation darkens it for transmission.
    for (const Material& m : scene.materials) {
      phong_.push_back(phong_approximation(m));
      if (m.model == Material::Model::metallic_roughness) phong_.back().diffuse = vec3(m.pbr.base_color);
    }
  }

  SaveResult write() {
    material_names();
    on_path_.assign(scene_.nodes.size(), 0);
    visit(scene_.root, mat4(1.f), true);

    std::ostringstream obj;
    obj << "# written by rayform convert";
    if (!scene_.source_path.empty()) obj << " from " << fs::path(scene_.source_path).filename().string();
    obj << "\n";
    const std::string mtl = safe_file_name(context_.stem) + ".mtl";
    for (size_t i = 0; i < scene_.materials.size(); ++i) used_materials_.insert(int(i));  // unused ones too
    if (!used_materials_.empty()) obj << "mtllib " << context_.out.side_reference(mtl) << "\n";
    obj << body_.str();
    context_.out.add(context_.path, obj.str());
    // The textures are beside the .mtl, which names them.
    if (!used_materials_.empty()) context_.out.add(context_.out.side_path(mtl), write_mtl());
    report();
    return SaveResult{context_.out.commit(), stored_triangles_};
  }

 private:
  // ---- materials -----------------------------------------------------------------

  void material_names() {
    std::set<std::string> used;
    for (const Material& m : scene_.materials) {
      std::string n = m.name;
      for (char& c : n)
        if (std::isspace(static_cast<unsigned char>(c))) c = '_';
      if (n.empty()) n = "material";
      std::string u = n;
      for (int k = 2; used.count(u); ++k) u = n + "_" + std::to_string(k);
      used.insert(u);
      names_.push_back(u);
    }
    default_name_ = "default";
    for (int k = 2; used.count(default_name_); ++k) default_name_ = "default_" + std::to_string(k);
  }

  // The MTL name of Scene material m (invalid: a white default material).
  const std::string& material_name(int m) {
    if (m < 0 || size_t(m) >= scene_.materials.size()) {
      used_default_ = true;
      used_materials_.insert(-1);
      return default_name_;
    }
    used_materials_.insert(m);
    return names_[size_t(m)];
  }

  std::string texture_file(int ti) {
    if (ti < 0 || size_t(ti) >= scene_.textures.size()) return {};
    auto it = textures_.find(ti);
    if (it != textures_.end()) return it->second;
    const Texture& t = scene_.textures[size_t(ti)];
    std::string base = texture_base_name(t);
    std::string file;
    try {
      std::string ext;
      std::vector<uint8_t> bytes = rayform::texture_file(t, {"png", "jpg", "bmp", "tga"}, &ext);
      file = safe_file_name(context_.stem + "_" + base) + "." + ext;
      for (int k = 2; used_files_.count(file); ++k)
        file = safe_file_name(context_.stem + "_" + base + "_" + std::to_string(k)) + "." + ext;
      used_files_.insert(file);
      context_.out.add(context_.out.side_path(file), std::move(bytes));
    } catch (const Error& e) {
      context_.note(std::string("texture '") + t.name + "' cannot be read (" + e.what() +
                    "); materials using it are untextured");
    }
    if (t.lookup == Texture::Lookup::course) course_lookup_.insert(t.name);
    if (t.filter == Texture::Filter::nearest) nearest_.insert(t.name);
    if (t.wrap_u == Texture::Wrap::mirror || t.wrap_v == Texture::Wrap::mirror || t.wrap_u != t.wrap_v)
      mirror_.insert(t.name);
    textures_[ti] = file;
    return file;
  }

  std::string write_mtl() {
    std::ostringstream o;
    o << "# written by rayform convert\n";
    for (int mi : used_materials_) {
      if (mi < 0) {
        o << "\nnewmtl " << default_name_ << "\nKd 1 1 1\nKs 0 0 0\nNs 0\nillum 1\n";
        continue;
      }
      const Material& m = phong_[size_t(mi)];
      std::string tex = m.diffuse_texture != invalid ? texture_file(m.diffuse_texture) : std::string();
      vec3 kd = m.diffuse;
      if (!tex.empty() && !m.texture_modulates) {
        // A course texture replaces the colour: Kd 1 x texel.
        if (kd != vec3(1.f)) replaced_.insert(m.name);
        kd = vec3(1.f);
      }
      o << "\nnewmtl " << names_[size_t(mi)] << "\n";
      o << "Kd " << format_vec3(kd) << "\n";
      o << "Ks " << format_vec3(m.specular) << "\n";
      o << "Ns " << format_float(m.shininess) << "\n";
      if (m.shininess == 0.f && m.specular != vec3(0.f)) ns_zero_.insert(m.name);
      if (m.emission != vec3(0.f)) o << "Ke " << format_vec3(m.emission) << "\n";
      if (m.refraction_index != 0.f) o << "Ni " << format_float(m.refraction_index) << "\n";
      o << "illum 2\n";
      if (m.alpha_cutoff >= 0.f) cutouts_.insert(m.name);
      if (!m.double_sided) single_sided_.insert(m.name);
      if (!m.two_sided_lighting && m.refraction_index == 0.f) one_side_lit_.insert(m.name);
      if (!tex.empty()) {
        const Texture& t = scene_.textures[size_t(m.diffuse_texture)];
        o << "map_Kd";
        if (!m.uv_transform.is_identity() && m.uv_transform.rotation == 0.f)
          o << " -s " << format_float(m.uv_transform.scale.x) << " " << format_float(m.uv_transform.scale.y) << " 1"
            << " -o " << format_float(m.uv_transform.offset.x) << " " << format_float(m.uv_transform.offset.y) << " 0";
        if (t.wrap_u == Texture::Wrap::clamp) o << " -clamp on";
        if (!t.srgb) o << " -colorspace linear";
        o << " " << tex << "\n";
      }
      if (m.bump_texture != invalid) {
        std::string bump = texture_file(m.bump_texture);
        if (!bump.empty()) o << "map_Bump " << bump << "\n";
      }
      if (scene_.materials[size_t(mi)].model == Material::Model::metallic_roughness)
        write_pbr_statements(scene_.materials[size_t(mi)], o);
    }
    return o.str();
  }

  // A texture statement's options and file: -s / -o of its transform (a
  // rotation cannot be said: noted), -clamp, then `extra` (e.g. -imfchan g).
  void texture_statement(const char* keyword, const TextureSlot& slot, const std::string& file,
                         const std::string& material, const std::string& extra, std::ostringstream& o) {
    const Texture& t = scene_.textures[size_t(slot.texture)];
    o << keyword;
    if (!slot.transform.is_identity()) {
      if (slot.transform.rotation != 0.f) pbr_lost_["rotated texture transforms"].insert(material);
      o << " -s " << format_float(slot.transform.scale.x) << " " << format_float(slot.transform.scale.y) << " 1"
        << " -o " << format_float(slot.transform.offset.x) << " " << format_float(slot.transform.offset.y) << " 0";
    }
    if (t.wrap_u == Texture::Wrap::clamp) o << " -clamp on";
    o << extra << " " << file << "\n";
  }

  // MTL's PBR extension (obj_pbr_material.h reads it back) after the Kd/Ks/Ns
  // approximation of a metallic-roughness material: Pr, Pm, their texture
  // as map_Pr / map_Pm of its G and B channels (-imfchan), map_Ke, norm, d,
  // Ni, Pc / Pcr, Ps; what MTL cannot say is noted.
  void write_pbr_statements(const Material& m, std::ostringstream& o) {
    const PbrMaterial& p = m.pbr;
    pbr_written_.insert(m.name);
    std::set<std::string> held = {"metallic-roughness texture", "normal texture", "emissive texture", "alpha blending",
                                  "sheen"};
    for (const std::string& field : pbr_fields_lost_in_phong(m))
      if (!held.count(field)) pbr_lost_[field].insert(m.name);
    if (p.transmission > 0.f) pbr_lost_["transmission"].insert(m.name);
    // A texture of the slot on uv set 0 (OBJ has one), else "" and noted.
    auto file_of = [&](const TextureSlot& slot, const char* field) -> std::string {
      if (!slot.used()) return {};
      if (slot.texcoord != 0) {
        pbr_lost_[std::string(field) + " on the second uv set"].insert(m.name);
        return {};
      }
      return texture_file(slot.texture);
    };
    o << "Pr " << format_float(p.roughness) << "\n";
    o << "Pm " << format_float(p.metallic) << "\n";
    if (std::string f = file_of(p.metallic_roughness_texture, "metallic-roughness texture"); !f.empty()) {
      texture_statement("map_Pr", p.metallic_roughness_texture, f, m.name, " -imfchan g", o);
      texture_statement("map_Pm", p.metallic_roughness_texture, f, m.name, " -imfchan b", o);
      packed_split_.insert(m.name);
      if (p.roughness != 1.f || p.metallic != 1.f)
        pbr_lost_["metallic and roughness factors beside their texture"].insert(m.name);
    }
    if (std::string f = file_of(p.emissive_texture, "emissive texture"); !f.empty())
      texture_statement("map_Ke", p.emissive_texture, f, m.name, "", o);
    if (std::string f = file_of(p.normal_texture, "normal texture"); !f.empty())
      texture_statement("norm", p.normal_texture, f, m.name,
                        p.normal_scale != 1.f ? " -bm " + format_float(p.normal_scale) : std::string(), o);
    if (p.alpha_mode == PbrMaterial::AlphaMode::blend) {
      o << "d " << format_float(std::clamp(p.base_color.a, 0.f, 1.f)) << "\n";
      if (p.base_color_texture.used()) {
        if (std::string f = file_of(p.base_color_texture, "base colour texture"); !f.empty())
          o << "map_d " << f << "\n";
      }
    }
    if (p.ior != PbrMaterial{}.ior && p.transmission == 0.f) o << "Ni " << format_float(p.ior) << "\n";
    if (p.clearcoat > 0.f) {
      o << "Pc " << format_float(p.clearcoat) << "\n";
      o << "Pcr " << format_float(p.clearcoat_roughness) << "\n";
    }
    const float sheen = std::max({p.sheen_color.r, p.sheen_color.g, p.sheen_color.b});
    if (sheen > 0.f) {
      o << "Ps " << format_float(sheen) << "\n";
      if (p.sheen_color != vec3(sheen) || p.sheen_roughness != obj::mtl_sheen_roughness)
        sheen_approximated_.insert(m.name);
    }
  }

  // ---- geometry ------------------------------------------------------------------------

  // Writes the world-space mesh's faces into the current section.
  void write_mesh(const Mesh& m, int node_material) {
    const bool has_n = m.normals.size() == m.positions.size();
    const bool has_uv = m.uvs.size() == m.positions.size();
    const bool has_c = m.colors.size() == m.positions.size();
    if (!has_n) faceted_ = true;
    const size_t faces = m.triangle_count();
    std::string current;
    std::map<std::pair<uint32_t, const UvTransform*>, std::array<uint32_t, 3>> mine;  // this mesh's vertices
    std::set<std::array<uint32_t, 3>> claimed;
    for (size_t f = 0; f < faces; ++f) {
      int mat = m.face_materials.size() == faces ? m.face_materials[f] : node_material;
      const std::string& mn = material_name(mat);
      if (mn != current) {
        body_ << "usemtl " << mn << "\n";
        current = mn;
      }
      const UvTransform* t = nullptr;
      if (mat >= 0 && size_t(mat) < scene_.materials.size()) {
        const Material& mm = phong_[size_t(mat)];
        if (mm.diffuse_texture != invalid && mm.uv_transform.rotation != 0.f) {
          t = &mm.uv_transform;
          baked_.insert(mm.name);
        }
      }
      uint32_t idx[3] = {m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
      for (uint32_t i : idx)
        if (i >= m.positions.size()) throw Error(context_.path + ": mesh '" + m.name + "' has an index out of range");
      vec3 face_n(0.f);
      if (!has_n) {
        vec3 c = glm::cross(m.positions[idx[1]] - m.positions[idx[0]], m.positions[idx[2]] - m.positions[idx[0]]);
        float len = glm::length(c);
        face_n = len > 0.f ? c / len : vec3(0.f, 0.f, 1.f);
      }
      std::string face = "f";
      for (uint32_t i : idx) {
        // New v/vt/vn lines go out before the face that uses them.
        std::array<uint32_t, 3> c;
        auto key = std::make_pair(i, t);
        if (auto it = mine.find(key); has_n && it != mine.end()) {
          c = it->second;
        } else {
          vec3 col = has_c ? m.colors[i] : vec3(1.f);
          c = {position(m.positions[i], col), has_uv ? texcoord(t ? t->apply(m.uvs[i]) : m.uvs[i]) : 0u,
               normal(has_n ? m.normals[i] : face_n)};
          if (has_n) {
            // Two vertices of one mesh with equal values stay two vertices:
            // readers merge corners by their (v, vt, vn) indices.
            if (!claimed.insert(c).second) {
              c[0] = new_position(m.positions[i], col);
              claimed.insert(c);
            }
            mine.emplace(key, c);
          }
        }
        face += ' ';
        face += std::to_string(c[0]);
        face += '/';
        if (has_uv) face += std::to_string(c[1]);
        face += '/';
        face += std::to_string(c[2]);
      }
      body_ << face;
      body_ << "\n";
    }
    stored_triangles_ += faces;
  }

  uint32_t position(vec3 p, vec3 c) {
    float f[6] = {p.x, p.y, p.z, c.r, c.g, c.b};
    auto it = positions_.find(bits<6>(f));
    if (it != positions_.end()) return it->second;
    uint32_t v = new_position(p, c);
    positions_.emplace(bits<6>(f), v);
    return v;
  }
  // A `v` line of its own (also for a value written before).
  uint32_t new_position(vec3 p, vec3 c) {
    body_ << "v " << format_vec3(p);
    if (any_colors_) body_ << " " << format_vec3(c);
    body_ << "\n";
    return ++v_count_;
  }
  uint32_t texcoord(vec2 uv) {
    float f[2] = {uv.x, uv.y};
    auto [it, inserted] = texcoords_.emplace(bits<2>(f), uint32_t(texcoords_.size() + 1));
    if (inserted) body_ << "vt " << format_float(uv.x) << " " << format_float(uv.y) << "\n";
    return it->second;
  }
  uint32_t normal(vec3 n) {
    float len = glm::length(n);
    if (len > 0.f && std::isfinite(len)) {
      if (std::abs(len - 1.f) > 1e-6f) n /= len;  // unit normals are kept bit for bit
    } else {
      ++zero_normals_;
    }
    float f[3] = {n.x, n.y, n.z};
    auto [it, inserted] = normals_.emplace(bits<3>(f), uint32_t(normals_.size() + 1));
    if (inserted) body_ << "vn " << format_vec3(n) << "\n";
    return it->second;
  }

  // One shape instance in world space.
  void write_shape(const Node& n, const mat4& world) {
    if (n.shape < 0) return;
    switch (n.shape_kind) {
      case ShapeKind::sphere:
        write_mesh(
            transform_mesh(tessellate_sphere(scene_.spheres.at(size_t(n.shape)), options_.sphere_segments), world),
            n.material);
        ++spheres_;
        break;
      case ShapeKind::plane: {
        Plane p = is_identity(world) ? scene_.planes.at(size_t(n.shape))
                                     : transform_plane(scene_.planes.at(size_t(n.shape)), world);
        vec3 around = extent_.empty() ? vec3(0.f) : extent_.center();
        float half = plane_quad_scale * (extent_.empty() ? 1.f : std::max(0.5f * glm::length(extent_.extent()), 1.f));
        plane_half_ = half;
        write_mesh(plane_quad(p, around, half), n.material);
        ++planes_;
        break;
      }
      case ShapeKind::triangle: {
        const Triangle& t = scene_.triangles.at(size_t(n.shape));
        Mesh m;
        for (const vec3& v : t.vertices) m.positions.push_back(transform_point(world, v));
        m.indices = {0, 1, 2};
        if (glm::determinant(mat3(world)) < 0.f) m.indices = {0, 2, 1};
        write_mesh(m, n.material);
        break;
      }
      case ShapeKind::mesh: {
        const Mesh& src = scene_.meshes.at(size_t(n.shape));
        if (is_identity(world)) {
          write_mesh(src, n.material);
        } else {
          write_mesh(transform_mesh(src, world), n.material);
          baked_transforms_ = true;
        }
        break;
      }
    }
    if (!is_identity(world)) baked_transforms_ = true;
  }

  // A node: its shape children (or itself, for a shape) as one section, then
  // its other children.
  void visit(int i, const mat4& parent, bool top) {
    if (i < 0 || size_t(i) >= scene_.nodes.size())
      throw Error(context_.path + ": scene node " + std::to_string(i) + " does not exist");
    if (on_path_[size_t(i)]) throw Error(context_.path + ": scene node " + std::to_string(i) + " is its own ancestor");
    on_path_[size_t(i)] = 1;
    const Node& n = scene_.nodes[size_t(i)];
    const mat4 world = n.kind == Node::Kind::group ? parent : parent * n.local;
    std::vector<int> shapes, others;
    if (n.kind == Node::Kind::shape) shapes.push_back(i);
    for (int c : n.children) {
      if (c >= 0 && size_t(c) < scene_.nodes.size() && scene_.nodes[size_t(c)].kind == Node::Kind::shape &&
          scene_.nodes[size_t(c)].children.empty())
        shapes.push_back(c);
      else others.push_back(c);
    }
    if (!shapes.empty()) {
      std::string name = n.name.empty() ? "object" : n.name;
      for (char& ch : name)
        if (ch == '\n' || ch == '\r') ch = ' ';
      body_ << "o " << name << "\n";
      ++sections_;
      for (int s : shapes) {
        const Node& sn = scene_.nodes[size_t(s)];
        write_shape(sn, s == i ? world : world * sn.local);
      }
    }
    nested_ |= !top && !others.empty();  // groups within groups: a hierarchy OBJ cannot hold
    for (int c : others) visit(c, world, false);
    on_path_[size_t(i)] = 0;
  }

  // ---- messages --------------------------------------------------------------------------

  void report() {
    if (!options_.flattened && (baked_transforms_ || nested_))
      context_.note(
          "OBJ has no transforms and no node hierarchy: transforms baked into the vertices, each node's shapes "
          "written as one 'o' section (" +
          std::to_string(sections_) + " section(s))");
    if (spheres_)
      context_.note(std::to_string(spheres_) + " sphere(s) tessellated (" + std::to_string(options_.sphere_segments) +
                    " segments; OBJ has no spheres)");
    if (planes_)
      context_.note(std::to_string(planes_) + " plane(s) written as square quads of half-size " +
                    format_float(plane_half_) + " around the scene (OBJ has no infinite planes)");
    if (zero_normals_)
      context_.note(std::to_string(zero_normals_) +
                    " zero-length normal(s) written as 'vn 0 0 0': OBJ readers make normals "
                    "from the faces there");
    if (faceted_) context_.note("meshes without normals (faceted) written with each face's normal as vn");
    if (!scene_.cameras.empty())
      context_.note(std::to_string(scene_.cameras.size()) + " camera(s) dropped (OBJ has no cameras)");
    if (!scene_.lights.empty()) {
      int point = 0;
      for (const Light& l : scene_.lights) point += l.kind != Light::Kind::directional;
      context_.note(std::to_string(scene_.lights.size()) + " light(s) dropped (" + std::to_string(point) +
                    " point or spot; OBJ has no lights)");
    }
    const Background& b = scene_.background;
    if (b.color != Background{}.color || b.ambient != vec3(0.f) || b.cube_map[0] != invalid)
      context_.note("background colour, ambient light and cube map dropped (OBJ has no background)");
    context_.note_names("materials", replaced_,
                        ": their texture replaces the colour (course), written as Kd 1 1 1 "
                        "(the diffuse colour, used where a shape has no uvs, is dropped)");
    context_.note_names("materials", baked_, ": rotated uv transform baked into the vt values");
    context_.note_names("materials", ns_zero_,
                        ": Ns 0 with a specular colour: OBJ readers (rayform's too) read it as no highlight");
    context_.note_names("materials", cutouts_, ": alpha cut-outs dropped");
    context_.note_names("materials", single_sided_, ": single-sided becomes double-sided (OBJ has no such flag)");
    context_.note_names("materials", one_side_lit_,
                        ": back faces will be shaded with their normals reversed towards "
                        "the viewer, as OBJ materials are (the source shades them with the normal as given)");
    context_.note_names("materials", pbr_written_,
                        ": metallic-roughness written as Kd/Ks/Ns (Ks and Ns from metallic, roughness, ior, specular "
                        "and clearcoat) and as MTL's PBR extension (Pr, Pm, Ke, norm, d, Ni, Pc, Pcr, Ps), which "
                        "rayform and Blender read back");
    context_.note_names("materials", packed_split_,
                        ": the metallic-roughness texture written as map_Pr -imfchan g and map_Pm -imfchan b (one "
                        "file, its green and blue channels); readers that ignore -imfchan read its luminance");
    context_.note_names("materials", sheen_approximated_,
                        ": sheen written as Ps, the sheen colour's largest component (MTL has neither a sheen colour "
                        "nor a sheen roughness)");
    for (const auto& [field, names] : pbr_lost_) context_.note_names("materials", names, ": " + field + " dropped");
    context_.note_names("textures", course_lookup_,
                        ": the course's texel centres (on whole numbers) are not expressible; "
                        "OBJ readers sample half a texel off");
    context_.note_names("textures", nearest_, ": nearest filtering dropped");
    context_.note_names("textures", mirror_, ": mirrored or mixed wrap modes become repeat");
  }

  const Scene& scene_;
  ObjWriteOptions options_;
  WriterContext context_;  // the output's path and names, its files, the messages
  Bounds3 extent_;
  std::ostringstream body_;
  std::vector<uint8_t> on_path_;
  std::vector<std::string> names_;
  std::string default_name_;
  bool used_default_ = false, any_colors_ = false, faceted_ = false, baked_transforms_ = false, nested_ = false;
  std::set<int> used_materials_;
  std::vector<Material> phong_;  // per Scene material: as the Phong model (material_approximation.h)
  std::set<std::string> pbr_written_, packed_split_, sheen_approximated_;
  std::map<std::string, std::set<std::string>> pbr_lost_;  // what MTL could not hold: field -> materials
  std::map<int, std::string> textures_;
  std::set<std::string> used_files_;
  std::map<std::array<uint32_t, 6>, uint32_t> positions_;
  std::map<std::array<uint32_t, 2>, uint32_t> texcoords_;
  std::map<std::array<uint32_t, 3>, uint32_t> normals_;
  size_t stored_triangles_ = 0;
  uint32_t v_count_ = 0;
  size_t zero_normals_ = 0;
  int spheres_ = 0, planes_ = 0, sections_ = 0;
  float plane_half_ = 0.f;
  std::set<std::string> replaced_, baked_, ns_zero_, cutouts_, single_sided_, one_side_lit_, course_lookup_, nearest_,
      mirror_;
};

}  // namespace

SaveResult write_obj_scene(const Scene& scene, const std::string& path, const ObjWriteOptions& options,
                           std::vector<std::string>* messages) {
  require_scene_root(scene, path);
  return ObjWriter(scene, path, options, messages).write();
}

}  // namespace rayform
