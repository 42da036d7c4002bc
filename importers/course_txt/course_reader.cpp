#include "rayform/importers/course_txt/course_reader.h"

#include "rayform/importers/course_txt/course_mesh.h"
#include "rayform/importers/course_txt/course_tokenizer.h"
#include "rayform/importers/file_bytes.h"
#include "rayform/base/error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>
#include <map>

namespace rayform {
namespace fs = std::filesystem;
namespace {

class CourseReader {
 public:
  CourseReader(std::string_view text, const std::string& path, CourseDialect dialect, const FileAccess& access)
      : tokens_(text, path), path_(path), dialect_(dialect), access_(access) {}

  CourseScene parse() {
    CourseScene out;
    out.dialect = dialect_;
    scene_.source_path = path_;
    while (!tokens_.at_end()) {
      Token t = tokens_.next();
      if (t.text == "PerspectiveCamera") parse_camera();
      else if (t.text == "Lights") parse_lights();
      else if (t.text == "Background") parse_background();
      else if (t.text == "Materials") parse_materials();
      else if (t.text == "Group") {
        if (scene_.root != invalid)
          warnings_.push_back(tokens_.where(t) + ": a second top-level Group replaces the first");
        scene_.root = parse_group(t);
      } else {
        tokens_.fail(t, "expected PerspectiveCamera, Lights, Background, Materials or Group");
      }
    }
    if (scene_.root == invalid) {
      Node root;
      root.name = "root";
      scene_.nodes.push_back(root);
      scene_.root = int(scene_.nodes.size()) - 1;
      warnings_.push_back(path_ + ": the scene has no Group: nothing to render but the background");
    }
    if (scene_.cameras.empty()) throw Error(path_ + ": the scene has no PerspectiveCamera");
    // `numLights 0` makes the ambient light white, so each object shows its
    // diffuse colour (a scene without a Lights block keeps its ambient).
    if (declared_no_lights_) scene_.background.ambient = vec3(1.f);
    // Check every MaterialIndex against the final material count.
    for (const auto& [node, token] : material_refs_)
      if (scene_.nodes[node].material >= int(scene_.materials.size()))
        tokens_.fail(token, "MaterialIndex " + std::to_string(scene_.nodes[node].material) +
                                " is out of range: the scene has " + std::to_string(scene_.materials.size()) +
                                " materials");
    if (dialect_ == CourseDialect::a5) give_a5_default_material();
    out.scene = std::move(scene_);
    out.warnings = std::move(warnings_);
    return out;
  }

 private:
  // a5: shapes declared before any MaterialIndex get the default material
  // with a5's shading rules (course_material), appended once.
  void give_a5_default_material() {
    int index = invalid;
    for (Node& n : scene_.nodes) {
      if (n.kind != Node::Kind::shape || n.material != invalid) continue;
      if (index == invalid) {
        Material m = course_material();
        m.name = "default";
        scene_.materials.push_back(m);
        index = int(scene_.materials.size()) - 1;
      }
      n.material = index;
    }
  }

  // A material with the defaults of the course and the dialect's rules: a5
  // has no highlight (shininess is read and ignored; specularColor weights
  // reflection and refraction), and a shadow falls only from the closest
  // surface before the light when it faces the shaded point.
  Material course_material() const {
    Material m;
    m.texture_modulates = false;
    if (dialect_ == CourseDialect::a5) {
      m.specular_highlight = false;
      m.back_faces_cast_shadows = false;
    }
    return m;
  }

  // Reads `{ key value... }` with the keys in any order; `on_key` consumes the
  // value of a key it knows and returns false for an unknown key.
  template <class Fn>
  void parse_block(const Token& opener, const char* expected_keys, Fn&& on_key) {
    tokens_.expect("{", opener.text);
    for (;;) {
      Token k = tokens_.next_or_fail(close_expected(opener));
      if (k.text == "}") return;
      if (!on_key(k)) tokens_.fail(k, std::string("expected one of ") + expected_keys + " or '}' in " + opener.text);
    }
  }

  std::string close_expected(const Token& opener) const {
    return "'}' to close " + opener.text + " opened at " + tokens_.line_col(opener);
  }

  // Reads `{ count_key n item... }`. `on_token(t)` parses what starts at token
  // t and returns whether it was one of the n items (false for a modifier such
  // as MaterialIndex). Returns n; fails at the first item beyond n, or at n
  // when fewer follow.
  template <class Fn>
  int parse_counted_list(const Token& opener, const std::string& count_key, const std::string& items, Fn&& on_token) {
    tokens_.expect("{", opener.text);
    tokens_.expect(count_key, opener.text);
    Token count_token = tokens_.peek_token();
    const int n = tokens_.count();
    int found = 0;
    for (;;) {
      Token t = tokens_.next_or_fail(close_expected(opener));
      if (t.text == "}") break;
      if (on_token(t) && ++found > n)
        tokens_.fail(t, "more " + items + " than " + count_key + " " + std::to_string(n) + " declares");
    }
    if (found != n)
      tokens_.fail(count_token,
                   count_key + " is " + std::to_string(n) + " but " + std::to_string(found) + " " + items + " follow");
    return n;
  }

  void parse_camera() {
    Token opener = tokens_.last();
    Camera c;
    c.aspect = Camera::Aspect::stretch;
    c.up_vector = dialect_ == CourseDialect::v2019 ? Camera::UpVector::raw : Camera::UpVector::orthonormal;
    bool has_angle = false;
    parse_block(opener, "center, direction, up, angle", [&](const Token& k) {
      if (k.text == "center") c.center = tokens_.vec3_value();
      else if (k.text == "direction") c.direction = tokens_.vec3_value();
      else if (k.text == "up") c.up = tokens_.vec3_value();
      else if (k.text == "angle") {
        c.fov_deg = tokens_.number();
        has_angle = true;
      } else return false;
      return true;
    });
    if (glm::length(c.direction) == 0.f) tokens_.fail(opener, "camera direction must not be zero");
    if (glm::length(glm::cross(c.direction, c.up)) == 0.f)
      tokens_.fail(opener, "camera up must not be zero or parallel to the direction");
    if (has_angle && !(c.fov_deg > 0.f && c.fov_deg < 180.f))
      tokens_.fail(opener, "camera angle must lie strictly between 0 and 180 degrees");
    scene_.cameras.assign(1, c);
  }

  void parse_lights() {
    Token opener = tokens_.last();
    std::vector<Light> lights;
    const int n = parse_counted_list(opener, "numLights", "lights", [&](const Token& t) {
      Light l;
      if (t.text == "DirectionalLight") {
        l.kind = Light::Kind::directional;
        parse_block(t, "direction, color", [&](const Token& k) {
          if (k.text == "direction") l.direction = tokens_.vec3_value();
          else if (k.text == "color") l.color = tokens_.vec3_value();
          else return false;
          return true;
        });
        if (glm::length(l.direction) == 0.f) tokens_.fail(t, "light direction must not be zero");
      } else if (t.text == "PointLight") {
        l.kind = Light::Kind::point;
        parse_block(t, "position, color, falloff", [&](const Token& k) {
          if (k.text == "position") l.position = tokens_.vec3_value();
          else if (k.text == "color") l.color = tokens_.vec3_value();
          else if (k.text == "falloff") {
            l.falloff = tokens_.number();
            if (l.falloff < 0.f) tokens_.fail(tokens_.last(), "falloff must not be negative");
          } else return false;
          return true;
        });
        // Falloff attenuates by 1 / (falloff d^2) in the 2019 dialect, by
        // 1 / (1 + falloff d^2) in a5, not at all in 2012.
        if (dialect_ == CourseDialect::v2012) l.falloff = 0.f;
        if (dialect_ == CourseDialect::a5) l.attenuation_constant = 1.f;
      } else {
        tokens_.fail(t, "expected DirectionalLight, PointLight or '}' in Lights");
      }
      lights.push_back(l);
      return true;
    });
    scene_.lights = std::move(lights);
    declared_no_lights_ = n == 0;
  }

  void parse_background() {
    Token opener = tokens_.last();
    parse_block(opener, "color, ambientLight, cubeMap", [&](const Token& k) {
      if (k.text == "color") scene_.background.color = tokens_.vec3_value();
      else if (k.text == "ambientLight") scene_.background.ambient = tokens_.vec3_value();
      else if (k.text == "cubeMap") parse_cube_map();
      else return false;
      return true;
    });
  }

  void parse_cube_map() {
    Token t = tokens_.next_or_fail("a cube map folder after cubeMap");
    scene_.background.cube_map_dir = t.text;
    fs::path dir = resolve(t, t.text, "cube map folder");
    // Faces in the order of Background::cube_map: .bmp files in a5, .png in 2012 and 2019.
    static const char* faces[6] = {"right", "left", "up", "down", "front", "back"};
    const std::string extension = cube_map_extension(dialect_);
    for (int i = 0; i < 6; ++i) {
      fs::path f = dir / (faces[i] + extension);
      if (!exists(f))
        tokens_.fail(t, "cube map folder has no " + std::string(faces[i]) + extension + " (" + f.string() + ")");
      check_access(t, "cube map face", (fs::path(t.text) / f.filename()).string(), f);
      Texture tex;
      tex.name = faces[i];
      tex.path = f.string();
      tex.lookup = Texture::Lookup::course;
      tex.wrap_u = tex.wrap_v = Texture::Wrap::clamp;
      scene_.textures.push_back(tex);
      scene_.background.cube_map[i] = int(scene_.textures.size()) - 1;
    }
  }

  void parse_materials() {
    Token opener = tokens_.last();
    std::vector<Material> mats;
    parse_counted_list(opener, "numMaterials", "materials", [&](const Token& t) {
      if (t.text != "Material" && t.text != "PhongMaterial")
        tokens_.fail(t, "expected Material, PhongMaterial or '}' in Materials");
      Material m = course_material();
      parse_block(t, "diffuseColor, specularColor, shininess, texture, bump, refractionIndex, Noise",
                  [&](const Token& k) {
                    if (k.text == "diffuseColor") m.diffuse = tokens_.vec3_value();
                    else if (k.text == "specularColor") m.specular = tokens_.vec3_value();
                    else if (k.text == "shininess") m.shininess = tokens_.number();
                    else if (k.text == "refractionIndex") {
                      m.refraction_index = tokens_.number();
                      // 0: opaque (reflective with specularColor); > 0: refractive.
                      if (m.refraction_index < 0.f)
                        tokens_.fail(tokens_.last(), "refractionIndex must be 0 (opaque) or positive, found '" +
                                                         shown(tokens_.last().text) + "'");
                    } else if (k.text == "texture")
                      m.diffuse_texture = texture(tokens_.next_or_fail("a texture file after texture"));
                    else if (k.text == "bump")
                      m.bump_texture = texture(tokens_.next_or_fail("a bump map file after bump"));
                    else if (k.text == "Noise") m.noise = parse_noise(k);
                    else return false;
                    return true;
                  });
      m.name = "material" + std::to_string(mats.size());
      mats.push_back(m);
      return true;
    });
    scene_.materials = std::move(mats);
  }

  // Noise { color c1 color c2 octaves k frequency f amplitude a } (a5); the
  // two colours are required, octaves must not be negative.
  SolidNoise parse_noise(const Token& opener) {
    SolidNoise n;
    n.enabled = true;
    int colors = 0;
    parse_block(opener, "color, octaves, frequency, amplitude", [&](const Token& k) {
      if (k.text == "color") {
        if (colors == 2) tokens_.fail(k, "Noise has two colours; a third follows");
        (colors++ == 0 ? n.color1 : n.color2) = tokens_.vec3_value();
      } else if (k.text == "octaves") {
        Token v = tokens_.peek_token();
        const float octaves = tokens_.number();
        if (!(octaves >= 0.f && octaves <= float(max_noise_octaves) && octaves == std::floor(octaves)))
          tokens_.fail(v, "octaves must be a whole number from 0 to " + std::to_string(max_noise_octaves) +
                              ", found '" + shown(v.text) + "'");
        n.octaves = int(octaves);
      } else if (k.text == "frequency") n.frequency = tokens_.number();
      else if (k.text == "amplitude") n.amplitude = tokens_.number();
      else return false;
      return true;
    });
    if (colors < 2)
      tokens_.fail(opener,
                   std::string("Noise needs two colours (color r g b twice), found ") + (colors ? "one" : "none"));
    return n;
  }

  int texture(const Token& file) {
    fs::path p = resolve(file, file.text, "texture");
    check_access(file, "texture", file.text, p);
    auto it = texture_cache_.find(p.string());
    if (it != texture_cache_.end()) return it->second;
    Texture t;
    t.name = file.text;
    t.path = p.string();
    t.lookup = Texture::Lookup::course;
    t.wrap_u = t.wrap_v = Texture::Wrap::clamp;
    t.srgb = false;  // course colours are raw
    scene_.textures.push_back(t);
    int index = int(scene_.textures.size()) - 1;
    texture_cache_[p.string()] = index;
    return index;
  }

  // Whether a file is there; a name the system cannot look up (too long, say)
  // is not.
  static bool exists(const fs::path& p) {
    std::error_code ec;
    return fs::exists(p, ec);
  }

  // Path relative to the scene file's folder, then (not confined) to the
  // working directory.
  fs::path resolve(const Token& t, const std::string& name, const char* what) {
    fs::path p(name);
    if (p.is_absolute()) {
      if (exists(p)) return p;
    } else {
      fs::path beside = fs::path(path_).parent_path() / p;
      if (exists(beside)) return beside;
      if (!access_.confine && exists(p)) return p;
    }
    tokens_.fail(t, std::string("cannot find ") + what + " '" + shown(name) + "' (looked beside the scene file" +
                        (access_.confine ? ")" : " and in the working directory)"));
  }

  // A file the scene names, before it is read (referenced_files.h).
  void check_access(const Token& t, const char* what, const std::string& name, const fs::path& resolved) {
    if (std::string problem = referenced_file_problem(path_, what, name, resolved, access_); !problem.empty())
      tokens_.fail(t, problem);
  }

  int add_node(Node n) {
    scene_.nodes.push_back(std::move(n));
    return int(scene_.nodes.size()) - 1;
  }

  // Groups and Transforms nest; each is one Scene node level (the top Group is
  // 1) and their shapes sit one level below.
  void enter_level(const Token& opener) {
    if (++depth_ + 1 > max_node_depth)
      tokens_.fail(opener, "Groups and Transforms are nested too deeply (a scene holds at most " +
                               std::to_string(max_node_depth) + " levels)");
  }

  int parse_group(const Token& opener) {
    enter_level(opener);
    Node g;
    g.kind = Node::Kind::group;
    g.name = "group";
    std::vector<int> children;
    parse_counted_list(opener, "numObjects", "objects", [&](const Token& t) {
      if (t.text == "MaterialIndex") {
        Token v = tokens_.peek_token();
        current_material_ = tokens_.count();
        current_material_token_ = v;
        return false;
      }
      children.push_back(parse_object(t));
      return true;
    });
    g.children = std::move(children);
    --depth_;
    return add_node(std::move(g));
  }

  int shape_node(ShapeKind kind, int shape, const char* name) {
    Node n;
    n.kind = Node::Kind::shape;
    n.name = name;
    n.shape_kind = kind;
    n.shape = shape;
    n.material = current_material_;
    int index = add_node(std::move(n));
    if (current_material_ != invalid) material_refs_.push_back({index, current_material_token_});
    return index;
  }

  static bool is_object_keyword(const std::string& w) {
    return w == "Group" || w == "Sphere" || w == "Plane" || w == "Triangle" || w == "TriangleMesh" || w == "Transform";
  }

  int parse_object(const Token& t) {
    if (t.text == "Group") return parse_group(t);
    if (t.text == "Sphere") {
      Sphere s;
      bool has_radius = false;
      parse_block(t, "center, radius", [&](const Token& k) {
        if (k.text == "center") s.center = tokens_.vec3_value();
        else if (k.text == "radius") {
          s.radius = tokens_.number();
          has_radius = true;
        } else return false;
        return true;
      });
      if (has_radius && !(s.radius > 0.f)) tokens_.fail(t, "sphere radius must be positive");
      scene_.spheres.push_back(s);
      return shape_node(ShapeKind::sphere, int(scene_.spheres.size()) - 1, "sphere");
    }
    if (t.text == "Plane") {
      Plane p;
      parse_block(t, "normal, offset", [&](const Token& k) {
        if (k.text == "normal") p.normal = tokens_.vec3_value();
        else if (k.text == "offset") p.offset = tokens_.number();
        else return false;
        return true;
      });
      float len = glm::length(p.normal);
      if (!(len > 0.f)) tokens_.fail(t, "plane normal must not be zero");
      // n . p = d with n as written: normalise n and d together.
      p.normal /= len;
      p.offset /= len;
      scene_.planes.push_back(p);
      return shape_node(ShapeKind::plane, int(scene_.planes.size()) - 1, "plane");
    }
    if (t.text == "Triangle") {
      Triangle tri;
      parse_block(t, "vertex0, vertex1, vertex2", [&](const Token& k) {
        if (k.text == "vertex0") tri.vertices[0] = tokens_.vec3_value();
        else if (k.text == "vertex1") tri.vertices[1] = tokens_.vec3_value();
        else if (k.text == "vertex2") tri.vertices[2] = tokens_.vec3_value();
        else return false;
        return true;
      });
      scene_.triangles.push_back(tri);
      return shape_node(ShapeKind::triangle, int(scene_.triangles.size()) - 1, "triangle");
    }
    if (t.text == "TriangleMesh") {
      int mesh = invalid;
      parse_block(t, "obj_file", [&](const Token& k) {
        if (k.text != "obj_file") return false;
        Token f = tokens_.next_or_fail("an OBJ file name after obj_file");
        mesh = load_mesh(f);
        return true;
      });
      if (mesh == invalid) tokens_.fail(t, "TriangleMesh needs an obj_file");
      return shape_node(ShapeKind::mesh, mesh, "mesh");
    }
    if (t.text == "Transform") return parse_transform(t);
    tokens_.fail(t,
                 "expected an object (Group, Sphere, Plane, Triangle, TriangleMesh, Transform), MaterialIndex or '}'");
  }

  int parse_transform(const Token& opener) {
    enter_level(opener);
    tokens_.expect("{", "Transform");
    mat4 m(1.f);
    int child = invalid;
    for (;;) {
      Token t = tokens_.next_or_fail(close_expected(opener));
      if (t.text == "}") break;
      // Right-multiplied: the first listed acts last on the object.
      if (t.text == "Scale") m = glm::scale(m, tokens_.vec3_value());
      else if (t.text == "UniformScale") m = glm::scale(m, vec3(tokens_.number()));
      else if (t.text == "Translate") m = glm::translate(m, tokens_.vec3_value());
      else if (t.text == "XRotate") m = glm::rotate(m, radians(tokens_.number()), vec3(1, 0, 0));
      else if (t.text == "YRotate") m = glm::rotate(m, radians(tokens_.number()), vec3(0, 1, 0));
      else if (t.text == "ZRotate") m = glm::rotate(m, radians(tokens_.number()), vec3(0, 0, 1));
      else if (t.text == "Rotate") {
        tokens_.expect("{", "Rotate");
        vec3 axis = tokens_.vec3_value();
        float deg = tokens_.number();
        tokens_.expect("}", "Rotate");
        if (glm::length(axis) == 0.f) tokens_.fail(t, "Rotate axis must not be zero");
        m = glm::rotate(m, radians(deg), glm::normalize(axis));
      } else if (t.text == "Matrix4f") {
        tokens_.expect("{", "Matrix4f");
        mat4 a;
        // Read column by column: numbers 13-15 hold the translation.
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) a[c][r] = tokens_.number();
        tokens_.expect("}", "Matrix4f");
        m = a * m;  // Matrix4f left-multiplies
      } else if (is_object_keyword(t.text)) {
        if (child != invalid) tokens_.fail(t, "a Transform holds exactly one object; expected '}'");
        child = parse_object(t);
      } else {
        tokens_.fail(
            t,
            "expected a transform (Scale, UniformScale, Translate, XRotate, YRotate, ZRotate, Rotate, "
            "Matrix4f), one object (Group, Sphere, Plane, Triangle, TriangleMesh, Transform) or '}' in Transform");
      }
    }
    if (child == invalid) tokens_.fail(opener, "Transform holds no object");
    Node n;
    n.kind = Node::Kind::transform;
    n.name = "transform";
    n.local = m;
    n.children = {child};
    --depth_;
    return add_node(std::move(n));
  }

  int load_mesh(const Token& file) {
    fs::path p = resolve(file, file.text, "mesh file");
    check_access(file, "mesh file", file.text, p);
    std::error_code ec;
    std::string key = fs::weakly_canonical(p, ec).string();
    if (ec) key = p.string();
    auto it = mesh_cache_.find(key);
    if (it != mesh_cache_.end()) return it->second;
    Mesh m;
    try {
      m = read_course_mesh(p.string(), dialect_);
    } catch (const Error& e) {
      tokens_.fail(file, std::string("cannot load mesh: ") + e.what());
    }
    m.name = file.text;
    scene_.meshes.push_back(std::move(m));
    int index = int(scene_.meshes.size()) - 1;
    mesh_cache_[key] = index;
    return index;
  }

  CourseTokenizer tokens_;
  std::string path_;
  CourseDialect dialect_;
  FileAccess access_;
  Scene scene_;
  std::vector<std::string> warnings_;
  bool declared_no_lights_ = false;
  int current_material_ = invalid;  // MaterialIndex stays in force across groups
  int depth_ = 0;                   // Groups and Transforms open around the parser
  Token current_material_token_;
  std::vector<std::pair<int, Token>> material_refs_;
  std::map<std::string, int> mesh_cache_, texture_cache_;
};

// Whether the cube map folder `dir` (as the scene writes it) holds a face of
// type `extension`, in the folder the parser takes (beside the scene, else
// the working directory).
bool cube_map_has_faces(const std::string& scene_path, const std::string& dir, const FileAccess& access,
                        const std::string& extension) {
  std::error_code ec;
  fs::path folder(dir);
  if (!folder.is_absolute()) {
    const fs::path beside = fs::path(scene_path).parent_path() / folder;
    if (fs::exists(beside, ec)) folder = beside;
    else if (access.confine) return false;
  }
  for (const char* face : {"right", "left", "up", "down", "front", "back"})
    if (fs::exists(folder / (face + extension), ec)) return true;
  return false;
}

}  // namespace

std::string cube_map_extension(CourseDialect dialect) { return dialect == CourseDialect::a5 ? ".bmp" : ".png"; }

CourseDialect detect_course_dialect(std::string_view text, const std::string& path, const FileAccess& access) {
  const CourseDialectMarks marks = course_dialect_marks(text);
  auto cube_faces = [&](CourseDialect d) {
    return !marks.cube_map_dir.empty() && cube_map_has_faces(path, marks.cube_map_dir, access, cube_map_extension(d));
  };
  // .bmp faces, Noise and refractionIndex are a5's alone (2019 reads .png
  // faces), whatever else the scene uses: a5's point lights have falloff.
  if (cube_faces(CourseDialect::a5) || marks.a5) return CourseDialect::a5;
  if (marks.v2019) return CourseDialect::v2019;
  // With a5 told apart by its .bmp faces, .png faces are 2019's.
  if (cube_faces(CourseDialect::v2019)) return CourseDialect::v2019;
  return CourseDialect::v2012;
}

CourseScene parse_course_scene(std::string_view text, const std::string& path, const CourseReadOptions& options) {
  const CourseDialect dialect = options.dialect ? *options.dialect : detect_course_dialect(text, path, options.access);
  return CourseReader(text, path, dialect, options.access).parse();
}

CourseScene read_course_scene(const std::string& path, const CourseReadOptions& options) {
  const FileBytes file(path, "scene file");
  return parse_course_scene(file.view(), path, options);
}

}  // namespace rayform
