#include "rayform/importers/course_txt/course_writer.h"

#include "rayform/importers/course_txt/course_mesh.h"
#include "rayform/image/output_files.h"
#include "rayform/importers/scene_writer.h"
#include "rayform/importers/writer_context.h"

#include "rayform/base/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/importers/text_format.h"
#include "rayform/importers/texture_files.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

namespace rayform {
namespace fs = std::filesystem;

std::vector<vec3> course_normals(const Mesh& mesh, const std::vector<uint32_t>& share, CourseDialect dialect) {
  std::vector<uint32_t> corners(mesh.indices.size());
  for (size_t c = 0; c < corners.size(); ++c) corners[c] = share[mesh.indices[c]];
  const std::vector<vec3> by_position = course_position_normals(mesh.positions, corners, dialect);
  std::vector<vec3> out(mesh.positions.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = by_position[share[i]];
  return out;
}

namespace {

// Vertices at one position with one normal are one course position; a mesh
// without normals shares nothing (the course then gives each face its own normal).
std::vector<uint32_t> sharing(const Mesh& m) {
  std::vector<uint32_t> share(m.positions.size());
  for (size_t i = 0; i < share.size(); ++i) share[i] = uint32_t(i);
  if (m.normals.size() != m.positions.size()) return share;
  std::map<std::array<uint32_t, 6>, uint32_t> first;
  for (size_t i = 0; i < share.size(); ++i) {
    std::array<uint32_t, 6> key;
    std::memcpy(key.data(), &m.positions[i], 12);
    std::memcpy(key.data() + 3, &m.normals[i], 12);
    share[i] = first.emplace(key, uint32_t(i)).first->second;
  }
  return share;
}

// Largest angle (degrees) between the mesh's own normals and the course's.
float normal_deviation(const Mesh& m, const std::vector<vec3>& course) {
  if (m.normals.size() != m.positions.size()) return 0.f;
  std::vector<uint8_t> used(m.positions.size(), 0);
  for (uint32_t i : m.indices) used[i] = 1;
  double worst = 0.0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    if (!used[i] || glm::length(m.normals[i]) == 0.f) continue;
    // atan2 of |a x b| and a . b: accurate for small angles, where acos is not.
    glm::dvec3 a = glm::normalize(glm::dvec3(m.normals[i])), b(course[i]);
    worst = std::max(worst, std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / std::numbers::pi);
  }
  return float(worst);
}

class CourseWriter {
 public:
  CourseWriter(const Scene& scene, const std::string& path, const CourseWriteOptions& options,
               std::vector<std::string>* messages)
      : s_(scene), options_(options), context_(scene, path, options.side_folder, messages) {
    if (std::string problem = course_side_folder_problem(path, options.side_folder); !problem.empty())
      throw Error(path + ": " + problem);
  }

  SaveResult write() {
    const bool course_source = fs::path(s_.source_path).extension() == ".txt";
    if (s_.cameras.empty()) {
      add_default_camera(s_);
      context_.note("the source has no camera: added one framing the scene (scene/scene_defaults.h)");
    }
    if (s_.lights.empty() && !course_source) {
      add_headlight(s_);
      context_.note(
          "the source has no light: added a white directional headlight along the view (the course would light a "
          "scene without lights by an ambient light of 1)");
    }
    dialect_ = options_.dialect ? *options_.dialect : needed_dialect();

    // The Group first: it decides the materials block (a default material).
    std::string group = top_group();
    std::ostringstream o;
    write_camera(o);
    write_lights(o);
    write_background(o);
    write_materials(o);
    o << group;
    report();
    context_.out.add(context_.path, o.str());
    for (const std::string& d : folders_) {
      std::error_code ec;
      fs::create_directories(d, ec);
      if (ec) throw Error(d + ": cannot create folder: " + ec.message());
    }
    return SaveResult{context_.out.commit(), stored_triangles_};
  }

 private:
  // ---- dialect -------------------------------------------------------------------

  bool raw_up_matters(const Camera& c) const {
    if (c.up_vector != Camera::UpVector::raw) return false;
    vec3 w = glm::normalize(c.direction);
    vec3 v = glm::cross(glm::normalize(glm::cross(w, c.up)), w);
    return glm::length(c.up - v) > 1e-6f;
  }

  CourseDialect needed_dialect() {
    // Materials of the 2012 assignment 5 (which has falloff too).
    for (const Material& m : s_.materials)
      if (m.noise.enabled || !m.specular_highlight || !m.back_faces_cast_shadows) {
        context_.note(
            "written in the a5 dialect (materials of the 2012 assignment 5: Noise, no highlight, its shadow rule)");
        return CourseDialect::a5;
      }
    const char* why = nullptr;
    for (const Light& l : s_.lights)
      if (l.kind != Light::Kind::directional && l.falloff > 0.f) why = "point lights with falloff";
    for (const Material& m : s_.materials)
      if (m.bump_texture != invalid) why = "bump maps";
    if (!s_.cameras.empty() && raw_up_matters(s_.cameras[0])) why = "a camera whose raw up vector is not orthonormal";
    if (!why)
      for (const Mesh& m : s_.meshes) {
        if (m.normals.size() != m.positions.size()) continue;
        std::vector<uint32_t> share = sharing(m);
        float d12 = normal_deviation(m, course_normals(m, share, CourseDialect::v2012));
        float d19 = normal_deviation(m, course_normals(m, share, CourseDialect::v2019));
        if (d19 < 1e-2f && d12 >= 1e-2f) why = "mesh normals made by the 2019 rule";
      }
    if (!why) return CourseDialect::v2012;
    context_.note(std::string("written in the 2019 dialect (") + why + ")");
    return CourseDialect::v2019;
  }

  // ---- header blocks --------------------------------------------------------------

  void write_camera(std::ostringstream& o) {
    const Camera& c = s_.cameras[0];
    if (s_.cameras.size() > 1)
      context_.note(std::to_string(s_.cameras.size() - 1) +
                    " camera(s) after the first dropped (the course has one camera)");
    float angle = c.fov_deg;
    if (c.projection == Camera::Projection::orthographic) {
      context_.note("orthographic camera written as a perspective camera of angle " + format_float(angle) +
                    " (the course has perspective cameras only)");
    }
    if (c.aspect == Camera::Aspect::fit)
      context_.note(
          "camera: the course stretches the view to the image's shape (no aspect correction): the same picture for "
          "square images only");
    if (dialect_ == CourseDialect::v2012 && raw_up_matters(c))
      context_.note("camera: its raw up vector (2019) becomes the orthonormal one in the 2012 dialect");
    o << "PerspectiveCamera {\n"
      << "    center " << format_vec3(c.center) << "\n"
      << "    direction " << format_vec3(c.direction) << "\n"
      << "    up " << format_vec3(c.up) << "\n"
      << "    angle " << format_float(angle) << "\n"
      << "}\n\n";
  }

  void write_lights(std::ostringstream& o) {
    o << "Lights {\n    numLights " << s_.lights.size() << "\n";
    int spots = 0, ranges = 0, falloffs = 0;
    for (const Light& l : s_.lights) {
      if (l.kind == Light::Kind::directional) {
        o << "    DirectionalLight {\n        direction " << format_vec3(l.direction) << "\n        color "
          << format_vec3(l.color) << "\n    }\n";
        continue;
      }
      if (l.kind == Light::Kind::spot) ++spots;
      if (l.range > 0.f) ++ranges;
      o << "    PointLight {\n        position " << format_vec3(l.position) << "\n        color "
        << format_vec3(l.color) << "\n";
      if (l.falloff > 0.f) {
        if (dialect_ != CourseDialect::v2012) o << "        falloff " << format_float(l.falloff) << "\n";
        else ++falloffs;
      }
      o << "    }\n";
    }
    o << "}\n\n";
    if (spots)
      context_.note(std::to_string(spots) + " spot light(s) written as point lights (the course has no spot lights)");
    if (ranges) context_.note(std::to_string(ranges) + " light range(s) dropped (the course has none)");
    if (falloffs)
      context_.note(std::to_string(falloffs) +
                    " point light(s) lose their falloff: the 2012 dialect does not attenuate (write "
                    "--dialect 2019 to keep it)");
    if (s_.lights.empty())
      context_.note(
          "no lights: the course lights such a scene by an ambient light of 1 (each pixel shows its diffuse colour)");
  }

  void write_background(std::ostringstream& o) {
    const Background& b = s_.background;
    o << "Background {\n    color " << format_vec3(b.color) << "\n    ambientLight " << format_vec3(b.ambient) << "\n";
    if (b.cube_map[0] != invalid) {
      std::string dir = safe_file_name(context_.stem + "_cubemap");
      static const char* faces[6] = {"right", "left", "up", "down", "front", "back"};
      bool ok = true;
      for (int i = 0; i < 6 && ok; ++i) {
        int t = b.cube_map[size_t(i)];
        if (t < 0 || size_t(t) >= s_.textures.size()) {
          ok = false;
          break;
        }
        try {
          // The dialect's file type: .bmp faces in a5, .png in the others.
          const std::string face_type = cube_map_extension(dialect_);
          std::string ext;
          std::vector<uint8_t> bytes = texture_file(s_.textures[size_t(t)], {face_type.substr(1)}, &ext);
          context_.out.add((fs::path(context_.out.side_path(dir)) / (std::string(faces[i]) + face_type)).string(),
                           std::move(bytes));
        } catch (const Error& e) {
          context_.note(std::string("cube map face ") + faces[i] + " cannot be read (" + e.what() +
                        "); cube map dropped");
          ok = false;
        }
      }
      if (ok) {
        folders_.push_back(context_.out.side_path(dir));
        o << "    cubeMap " << context_.out.side_reference(dir) << "\n";
      }
    }
    o << "}\n\n";
  }

  void write_materials(std::ostringstream& o) {
    size_t n = s_.materials.size() + (need_default_ ? 1 : 0);
    o << "Materials {\n    numMaterials " << n << "\n";
    std::set<std::string> emissive, cutouts, modulated, vertex_colored, bumps_dropped, single_sided, two_sided;
    for (const Material& m : s_.materials) {
      o << "    PhongMaterial {\n"
        << "        diffuseColor " << format_vec3(m.diffuse) << "\n"
        << "        specularColor " << format_vec3(m.specular) << "\n"
        << "        shininess " << format_float(m.shininess) << "\n";
      if (m.diffuse_texture != invalid) {
        std::string f = texture(m.diffuse_texture);
        if (!f.empty()) o << "        texture " << f << "\n";
        if (m.texture_modulates && m.diffuse != vec3(1.f)) modulated.insert(m.name);
      }
      if (m.bump_texture != invalid) {
        if (dialect_ == CourseDialect::v2019) {
          std::string f = texture(m.bump_texture);
          if (!f.empty()) o << "        bump " << f << "\n";
        } else {
          bumps_dropped.insert(m.name);
        }
      }
      if (m.refraction_index != 0.f) o << "        refractionIndex " << format_float(m.refraction_index) << "\n";
      if (m.noise.enabled)
        o << "        Noise {\n            color " << format_vec3(m.noise.color1) << "\n            color "
          << format_vec3(m.noise.color2) << "\n            octaves " << m.noise.octaves << "\n            frequency "
          << format_float(m.noise.frequency) << "\n            amplitude " << format_float(m.noise.amplitude)
          << "\n        }\n";
      o << "    }\n";
      if (m.emission != vec3(0.f)) emissive.insert(m.name);
      if (m.alpha_cutoff >= 0.f) cutouts.insert(m.name);
      if (!m.double_sided) single_sided.insert(m.name);
      if (m.two_sided_lighting && m.refraction_index == 0.f) two_sided.insert(m.name);
    }
    if (need_default_) o << "    PhongMaterial {\n        diffuseColor 1 1 1\n    }\n";
    o << "}\n\n";
    if (!emissive.empty())
      context_.note("materials " + quoted_list(emissive) + ": emission dropped (the course has none)");
    if (!cutouts.empty())
      context_.note("materials " + quoted_list(cutouts) + ": alpha cut-outs dropped (the course draws them opaque)");
    if (!two_sided.empty())
      context_.note("materials " + quoted_list(two_sided) +
                    ": back faces are shaded with their normals as given, not reversed " +
                    "towards the viewer (the course format's convention)");
    if (!single_sided.empty())
      context_.note("materials " + quoted_list(single_sided) +
                    ": single-sided becomes double-sided (the course has no such flag)");
    if (!modulated.empty())
      context_.note(
          "materials " + quoted_list(modulated) +
          ": the diffuse colour that multiplies the texture is dropped (a course texture replaces the colour)");
    if (!bumps_dropped.empty())
      context_.note("materials " + quoted_list(bumps_dropped) +
                    ": bump maps dropped (2012 dialect; write --dialect 2019)");
    if (need_default_)
      context_.note("shapes without a material follow a MaterialIndex: they use an added white material " +
                    std::to_string(s_.materials.size()));
    for (const Mesh& m : s_.meshes)
      if (!m.colors.empty()) vertex_colored.insert(m.name);
    if (!vertex_colored.empty())
      context_.note("meshes " + quoted_list(vertex_colored) + ": vertex colours dropped (the course has none)");
  }

  // The BMP file of a Scene texture ("" when it cannot be read).
  std::string texture(int ti) {
    if (ti < 0 || size_t(ti) >= s_.textures.size()) return {};
    auto it = textures_.find(ti);
    if (it != textures_.end()) return it->second;
    const Texture& t = s_.textures[size_t(ti)];
    std::string base = texture_base_name(t);
    std::string file = unique_file(safe_file_name(context_.stem + "_" + base), ".bmp");
    try {
      std::string ext;
      std::vector<uint8_t> bytes = texture_file(t, {"bmp"}, &ext);
      context_.out.add(context_.out.side_path(file), std::move(bytes));
      file = context_.out.side_reference(file);
      if (!t.pixels.empty() && t.channels == 4) {
        for (size_t i = 3; i < t.pixels.size(); i += 4)
          if (t.pixels[i] != 255) {
            alpha_dropped_.insert(t.name);
            break;
          }
      }
    } catch (const Error& e) {
      context_.note(std::string("texture '") + t.name + "' cannot be read (" + e.what() +
                    "); materials using it are untextured");
      file.clear();
    }
    if (t.srgb) srgb_.insert(t.name);
    if (t.lookup != Texture::Lookup::course) half_texel_.insert(t.name);
    if (t.wrap_u != Texture::Wrap::clamp || t.wrap_v != Texture::Wrap::clamp) repeat_.insert(t.name);
    if (t.filter == Texture::Filter::nearest) nearest_.insert(t.name);
    textures_[ti] = file;
    return file;
  }

  std::string unique_file(const std::string& base, const std::string& ext) {
    std::string f = base + ext;
    for (int k = 2; used_files_.count(f); ++k) f = base + "_" + std::to_string(k) + ext;
    used_files_.insert(f);
    return f;
  }

  // ---- meshes ----------------------------------------------------------------------

  // The OBJ file of one part of a mesh (faces of material `part`, or all when
  // invalid), uvs transformed by material `uv_material`'s transform if any.
  std::string mesh_file(int mi, int part, int uv_material) {
    const Mesh& m = s_.meshes.at(size_t(mi));
    const UvTransform* t = nullptr;
    if (uv_material >= 0 && size_t(uv_material) < s_.materials.size() &&
        !s_.materials[size_t(uv_material)].uv_transform.is_identity() && !m.uvs.empty() &&
        s_.materials[size_t(uv_material)].diffuse_texture != invalid)
      t = &s_.materials[size_t(uv_material)].uv_transform;
    auto key = std::make_tuple(mi, part, t ? uv_material : invalid);
    auto it = mesh_files_.find(key);
    if (it != mesh_files_.end()) return it->second;
    if (t) baked_uvs_.insert(s_.materials[size_t(uv_material)].name);

    // The faces of this part.
    Mesh sub;
    sub.positions = m.positions;
    sub.normals = m.normals;
    if (part == invalid || m.face_materials.empty()) {
      sub.indices = m.indices;
    } else {
      for (size_t f = 0; f < m.triangle_count(); ++f)
        if (m.face_materials[f] == part)
          sub.indices.insert(sub.indices.end(), m.indices.begin() + long(3 * f), m.indices.begin() + long(3 * f + 3));
    }
    for (uint32_t i : sub.indices)
      if (i >= m.positions.size()) throw Error(context_.path + ": mesh '" + m.name + "' has an index out of range");
    const bool has_normals = m.normals.size() == m.positions.size();
    const bool has_uvs = m.uvs.size() == m.positions.size();
    std::vector<uint32_t> share = sharing(m);

    std::ostringstream o, uvs;
    std::vector<int64_t> vindex(m.positions.size(), -1);
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> uv_index;
    uint32_t nv = 0, nt = 0;
    std::ostringstream faces;
    for (size_t c = 0; c < sub.indices.size(); ++c) {
      uint32_t i = sub.indices[c];
      uint32_t vi;
      if (has_normals) {
        uint32_t rep = share[i];
        if (vindex[rep] < 0) {
          vindex[rep] = nv++;
          o << "v " << format_vec3(m.positions[rep]) << "\n";
        }
        vi = uint32_t(vindex[rep]);
      } else {
        vi = nv++;  // unshared: the course gives each face its own normal
        o << "v " << format_vec3(m.positions[i]) << "\n";
      }
      uint32_t ti = 0;
      if (has_uvs) {
        vec2 uv = t ? t->apply(m.uvs[i]) : m.uvs[i];
        std::pair<uint32_t, uint32_t> k;
        std::memcpy(&k.first, &uv.x, 4);
        std::memcpy(&k.second, &uv.y, 4);
        auto [u, inserted] = uv_index.emplace(k, nt);
        if (inserted) {
          ++nt;
          uvs << "vt " << format_float(uv.x) << " " << format_float(uv.y) << "\n";
        }
        ti = u->second;
      }
      if (c % 3 == 0) faces << "f";
      faces << " " << (vi + 1);
      if (has_uvs) faces << "/" << (ti + 1);
      if (c % 3 == 2) faces << "\n";
    }
    o << uvs.str() << faces.str();

    // How far the course's own normals will be from the source's.
    if (has_normals) {
      float dev = normal_deviation(sub, course_normals(sub, share, dialect_));
      if (dev > 0.01f) {
        normal_deviation_ = std::max(normal_deviation_, dev);
        normals_changed_.insert(m.name);
      }
    }
    // Equal meshes (e.g. one mesh read back from glTF as a copy per material) share a file.
    std::string text = o.str();
    if (auto same = mesh_texts_.find(text); same != mesh_texts_.end()) {
      mesh_files_[key] = same->second;
      return same->second;
    }
    std::string base = fs::path(m.name.empty() ? "mesh" : m.name).stem().string();
    if (part != invalid && !m.face_materials.empty()) base += "_" + std::to_string(part);
    std::string file = unique_file(safe_file_name(context_.stem + "_" + base), ".obj");
    stored_triangles_ += sub.indices.size() / 3;
    context_.out.add(context_.out.side_path(file), text);
    file = context_.out.side_reference(file);
    mesh_files_[key] = file;
    mesh_texts_.emplace(std::move(text), file);
    return file;
  }

  // ---- the node tree -------------------------------------------------------------------

  // The parts a shape node is written as: (material, mesh part) pairs.
  std::vector<std::pair<int, int>> parts(const Node& n) const {
    if (n.shape < 0) return {};
    if (n.shape_kind == ShapeKind::mesh) {
      const Mesh& m = s_.meshes.at(size_t(n.shape));
      if (m.face_materials.size() == m.triangle_count() && !m.face_materials.empty()) {
        std::vector<std::pair<int, int>> out;
        std::set<int> seen;
        for (int fm : m.face_materials)
          if (seen.insert(fm).second) out.emplace_back(fm, fm);
        return out;
      }
    }
    return {{n.material, invalid}};
  }

  bool group_like(const Node& n) const {
    return n.kind == Node::Kind::group || (n.kind == Node::Kind::transform && is_identity(n.local));
  }

  const Node& node(int i) const {
    if (i < 0 || size_t(i) >= s_.nodes.size())
      throw Error(context_.path + ": scene node " + std::to_string(i) + " does not exist");
    return s_.nodes[size_t(i)];
  }

  int children_objects(const Node& n) {
    int sum = 0;
    for (int c : n.children) sum += objects(c);
    return sum;
  }

  // How many course objects node i adds to the group that holds it.
  int objects(int i) {
    const Node& n = node(i);
    if (objects_.empty()) objects_.assign(s_.nodes.size(), -1);
    if (objects_[size_t(i)] >= 0) return objects_[size_t(i)];
    if (++depth_ > 10000) throw Error(context_.path + ": the node graph is too deep or has a cycle");
    int r;
    if (n.kind == Node::Kind::shape) {
      int p = int(parts(n).size());
      r = is_identity(n.local) ? p : (p > 0 ? 1 : 0);
    } else {
      r = children_objects(n) > 0 ? 1 : 0;
    }
    --depth_;
    objects_[size_t(i)] = r;
    return r;
  }

  // When node i is written as one shape (through groups and transforms that
  // wrap it alone), the material of that shape.
  bool leaf_material(int i, int* material) {
    const Node& n = node(i);
    if (n.kind == Node::Kind::shape) {
      auto p = parts(n);
      if (p.size() != 1) return false;
      *material = p[0].first;
      return true;
    }
    if (children_objects(n) != 1) return false;
    for (int c : n.children)
      if (objects(c) > 0) return leaf_material(c, material);
    return false;
  }

  void set_material(int m, std::ostringstream& o, const std::string& pad) {
    int k = m;
    if (m < 0 || size_t(m) >= s_.materials.size()) {
      if (current_ == -1) return;  // nothing set yet: the reader's "no material"
      need_default_ = true;
      k = int(s_.materials.size());
    }
    if (k == current_) return;
    o << pad << "MaterialIndex " << k << "\n";
    current_ = k;
  }

  std::string matrix_text(const mat4& m) {
    std::string s = "Matrix4f {";
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        s += ' ';
        s += format_float(m[c][r]);
      }
    return s + " }";
  }

  void shape_text(const Node& n, int part, int material, std::ostringstream& o, const std::string& pad) {
    switch (n.shape_kind) {
      case ShapeKind::sphere: {
        const Sphere& s = s_.spheres.at(size_t(n.shape));
        o << pad << "Sphere {\n"
          << pad << "    center " << format_vec3(s.center) << "\n"
          << pad << "    radius " << format_float(s.radius) << "\n"
          << pad << "}\n";
        break;
      }
      case ShapeKind::plane: {
        const Plane& p = s_.planes.at(size_t(n.shape));
        o << pad << "Plane {\n"
          << pad << "    normal " << format_vec3(p.normal) << "\n"
          << pad << "    offset " << format_float(p.offset) << "\n"
          << pad << "}\n";
        break;
      }
      case ShapeKind::triangle: {
        const Triangle& t = s_.triangles.at(size_t(n.shape));
        o << pad << "Triangle {\n";
        for (int k = 0; k < 3; ++k) o << pad << "    vertex" << k << " " << format_vec3(t.vertices[size_t(k)]) << "\n";
        o << pad << "}\n";
        break;
      }
      case ShapeKind::mesh:
        o << pad << "TriangleMesh {\n"
          << pad << "    obj_file " << mesh_file(n.shape, part, material) << "\n"
          << pad << "}\n";
        break;
    }
  }

  // Writes node i's objects into the group body being written.
  void emit(int i, std::ostringstream& o, const std::string& pad) {
    const Node& n = node(i);
    if (objects(i) == 0) return;
    int leaf = invalid;
    if (leaf_material(i, &leaf)) set_material(leaf, o, pad);  // before any Transform around it
    if (n.kind == Node::Kind::shape) {
      auto p = parts(n);
      if (is_identity(n.local)) {
        for (auto [material, part] : p) {
          set_material(material, o, pad);
          shape_text(n, part, material, o, pad);
        }
        return;
      }
      o << pad << "Transform {\n" << pad << "    " << matrix_text(n.local) << "\n";
      if (p.size() == 1) {
        shape_text(n, p[0].second, p[0].first, o, pad + "    ");
      } else {
        o << pad << "    Group {\n" << pad << "        numObjects " << p.size() << "\n";
        for (auto [material, part] : p) {
          set_material(material, o, pad + "        ");
          shape_text(n, part, material, o, pad + "        ");
        }
        o << pad << "    }\n";
      }
      o << pad << "}\n";
      return;
    }
    const int sum = children_objects(n);
    if (group_like(n)) {
      if (sum == 1) {  // nothing to group: the one object alone
        for (int c : n.children) emit(c, o, pad);
        return;
      }
      write_group(n, sum, o, pad);
      return;
    }
    o << pad << "Transform {\n" << pad << "    " << matrix_text(n.local) << "\n";
    if (sum == 1) {
      for (int c : n.children) emit(c, o, pad + "    ");
    } else {
      write_group(n, sum, o, pad + "    ");
    }
    o << pad << "}\n";
  }

  void write_group(const Node& n, int sum, std::ostringstream& o, const std::string& pad) {
    o << pad << "Group {\n" << pad << "    numObjects " << sum << "\n";
    for (int c : n.children) emit(c, o, pad + "    ");
    o << pad << "}\n";
  }

  std::string top_group() {
    std::ostringstream o;
    int r = s_.root;
    // Groups that hold one group only are not written around it.
    for (;;) {
      const Node& n = node(r);
      if (!group_like(n) || children_objects(n) != 1) break;
      int only = invalid;
      for (int c : n.children)
        if (objects(c) > 0) only = c;
      if (only == invalid || !group_like(node(only)) || children_objects(node(only)) < 2) break;
      r = only;
    }
    const Node& n = node(r);
    if (group_like(n)) {
      int sum = children_objects(n);
      if (sum == 0) context_.note("the scene has no shapes: the Group is empty");
      write_group(n, sum, o, "");
    } else {
      o << "Group {\n    numObjects 1\n";
      emit(r, o, "    ");
      o << "}\n";
    }
    return o.str();
  }

  // ---- messages -------------------------------------------------------------------------

  void report() {
    if (!normals_changed_.empty())
      context_.note(
          "meshes " + quoted_list(normals_changed_) +
          ": the course computes vertex normals from the faces (its meshes carry none); they differ from the source's "
          "by up to " +
          format_float(std::round(normal_deviation_ * 100.f) / 100.f) + " degrees");
    if (!baked_uvs_.empty())
      context_.note("materials " + quoted_list(baked_uvs_) +
                    ": uv transform baked into the uvs of their meshes' OBJ files");
    if (!srgb_.empty())
      context_.note("textures " + quoted_list(srgb_) +
                    ": sRGB-encoded texels are read raw (linear) by the course; pixels kept as they are");
    if (!half_texel_.empty())
      context_.note("textures " + quoted_list(half_texel_) +
                    ": the course samples with texel centres on whole numbers (half a texel off "
                    "the usual convention)");
    if (!repeat_.empty())
      context_.note("textures " + quoted_list(repeat_) + ": the course clamps uvs to the image (no repeat or mirror)");
    if (!nearest_.empty())
      context_.note("textures " + quoted_list(nearest_) +
                    ": nearest filtering dropped (the course filters bilinearly)");
    if (!alpha_dropped_.empty())
      context_.note("textures " + quoted_list(alpha_dropped_) + ": alpha dropped (24-bit BMP)");
  }

  Scene s_;
  CourseWriteOptions options_;
  WriterContext context_;  // the output's path and names, its files, the messages
  CourseDialect dialect_ = CourseDialect::v2012;
  int current_ = -1;
  bool need_default_ = false;
  int depth_ = 0;
  std::vector<int> objects_;  // per node: objects(i), -1 not yet known
  size_t stored_triangles_ = 0;
  float normal_deviation_ = 0.f;
  std::map<int, std::string> textures_;
  std::map<std::tuple<int, int, int>, std::string> mesh_files_;
  std::map<std::string, std::string> mesh_texts_;  // OBJ text -> file
  std::set<std::string> used_files_;
  std::vector<std::string> folders_;
  std::set<std::string> normals_changed_, baked_uvs_, srgb_, half_texel_, repeat_, nearest_, alpha_dropped_;
};

}  // namespace

std::string course_side_folder_problem(const std::string& path, const std::string& side_folder) {
  // The course reads a file name up to white space.
  if (OutputFiles(path, side_folder).side_reference("").find_first_of(" \t\r\n") == std::string::npos) return {};
  return "a course .txt cannot name files in '" + side_folder + "' (the path to it from the .txt has white space)";
}

SaveResult write_course_scene(const Scene& scene, const std::string& path, const CourseWriteOptions& options,
                              std::vector<std::string>* messages) {
  require_scene_root(scene, path);
  return CourseWriter(scene, path, options, messages).write();
}

}  // namespace rayform
