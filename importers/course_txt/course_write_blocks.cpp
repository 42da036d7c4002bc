// The course writer's blocks before the Group (CourseWriter,
// course_writer_internal.h): PerspectiveCamera, Lights, Background (its cube
// map faces as files in a folder beside the .txt) and Materials, with the
// textures they name as BMP files.
#include "rayform/importers/course_txt/course_writer_internal.h"

#include "rayform/importers/course_txt/course_reader.h"
#include "rayform/base/error.h"
#include "rayform/importers/text_format.h"
#include "rayform/importers/texture_files.h"

#include <filesystem>
#include <set>
#include <sstream>

namespace rayform::course_detail {
namespace fs = std::filesystem;

void CourseWriter::write_camera(std::ostringstream& o) {
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

void CourseWriter::write_lights(std::ostringstream& o) {
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
    o << "    PointLight {\n        position " << format_vec3(l.position) << "\n        color " << format_vec3(l.color)
      << "\n";
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

void CourseWriter::write_background(std::ostringstream& o) {
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

void CourseWriter::write_materials(std::ostringstream& o) {
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
  context_.note_names("materials", emissive, ": emission dropped (the course has none)");
  context_.note_names("materials", cutouts, ": alpha cut-outs dropped (the course draws them opaque)");
  context_.note_names("materials", two_sided,
                      ": back faces are shaded with their normals as given, not reversed "
                      "towards the viewer (the course format's convention)");
  context_.note_names("materials", single_sided, ": single-sided becomes double-sided (the course has no such flag)");
  context_.note_names(
      "materials", modulated,
      ": the diffuse colour that multiplies the texture is dropped (a course texture replaces the colour)");
  context_.note_names("materials", pbr_approximated_,
                      ": metallic-roughness approximated as Phong (diffuse = base colour and its texture; specular "
                      "and shininess from metallic, roughness, ior, specular and clearcoat; transmission as "
                      "refraction)");
  for (const auto& [field, names] : pbr_lost_) context_.note_names("materials", names, ": " + field + " dropped");
  context_.note_names("materials", bumps_dropped, ": bump maps dropped (2012 dialect; write --dialect 2019)");
  if (need_default_)
    context_.note("shapes without a material follow a MaterialIndex: they use an added white material " +
                  std::to_string(s_.materials.size()));
  for (const Mesh& m : s_.meshes)
    if (!m.colors.empty()) vertex_colored.insert(m.name);
  context_.note_names("meshes", vertex_colored, ": vertex colours dropped (the course has none)");
}

// The BMP file of a Scene texture ("" when it cannot be read).
std::string CourseWriter::texture(int ti) {
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

}  // namespace rayform::course_detail
