// The one internal scene every importer fills and every writer and the
// renderer read: plain data in arrays, integer handles, no virtual classes and
// no rendering state (Yocto/GL style). The node hierarchy is kept as the file
// wrote it so that writers can reproduce it; `prepare` flattens it for rendering.
#pragma once

#include "rayform/math/math.h"
#include "rayform/scene/pbr_material.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

// Handle value meaning "none".
inline constexpr int invalid = -1;

// Perspective or orthographic pinhole camera, world space.
struct Camera {
  enum class Projection : uint8_t { perspective, orthographic };
  // How the image plane's vertical axis is formed from `up`.
  enum class UpVector : uint8_t {
    orthonormal,  // v = u x w (course 2012 and all asset formats)
    raw,          // v = up as written, not orthogonalised (course 2019)
  };
  enum class Aspect : uint8_t {
    stretch,  // x and y both span [-1, 1] whatever the image shape (the course)
    fit,      // fov_deg spans the vertical axis; x scaled by width/height (assets)
  };
  std::string name;
  Projection projection = Projection::perspective;
  UpVector up_vector = UpVector::orthonormal;
  Aspect aspect = Aspect::stretch;
  vec3 center{0.f, 0.f, 0.f};
  vec3 direction{0.f, 0.f, -1.f};
  vec3 up{0.f, 1.f, 0.f};
  float fov_deg = 30.f;      // full opening angle (perspective), degrees
  float ortho_height = 2.f;  // full height of the view (orthographic), world units
};

struct Light {
  enum class Kind : uint8_t { directional, point, spot };
  std::string name;
  Kind kind = Kind::directional;
  vec3 direction{0.f, 0.f, -1.f};  // direction the light travels (directional, spot)
  vec3 position{0.f};              // point, spot
  // Linear colour times intensity, in the course's units: a light of colour
  // c lights a white diffuse surface facing it with the radiance c, under
  // the course's Phong model (c K cos) and the physically based one alike
  // (irradiance E = pi c, Lambert K / pi). A glTF light of `intensity` I
  // (candela for point and spot, lux for directional) and colour C has
  // c = C I / pi.
  vec3 color{1.f};
  // Point/spot attenuation: colour / (attenuation_constant + falloff * distance^2)
  // when falloff > 0; falloff 0 means none (course 2012). attenuation_constant is
  // 0 for the course's 2019 dialect, 1 for its assignment 5 (a5).
  float falloff = 0.f;
  float attenuation_constant = 0.f;
  float range = 0.f;  // glTF range, 0 = infinite
  float spot_inner_deg = 0.f, spot_outer_deg = 45.f;
};

struct Texture {
  enum class Wrap : uint8_t { repeat, clamp, mirror };
  enum class Filter : uint8_t { linear, nearest };
  // Where texel centres lie: the course samples with texel centres on whole
  // numbers (x = u W, bilinear between floor(x) and floor(x)+1, clamped);
  // the asset formats use centres at half-integers (x = u W - 0.5).
  enum class Lookup : uint8_t { course, standard };
  std::string name;
  std::string path;  // file to decode, resolved to an openable path by the importer
  // Already decoded pixels (e.g. images embedded in glTF), row 0 = top; when
  // empty the texture is decoded from `path` at prepare time.
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
  bool srgb = false;  // colour data stored sRGB-encoded (decoded to linear at prepare)
  Wrap wrap_u = Wrap::repeat, wrap_v = Wrap::repeat;
  Filter filter = Filter::linear;
  Lookup lookup = Lookup::standard;
};

// Solid noise replacing a material's diffuse colour in the diffuse term (the
// course's a5 `Noise`; the ambient term keeps the diffuse colour): at world
// point p, M = sin(frequency * p.x + amplitude * sum_{i < octaves}
// perlin_noise(2^i p) / 2^i), w = (M + 1) / 2, colour = w color1 + (1 - w) color2
// (math/perlin_noise.h).
struct SolidNoise {
  bool enabled = false;
  vec3 color1{0.f}, color2{0.f};
  int octaves = 0;
  float frequency = 1.f, amplitude = 1.f;
};

// A surface's material: one of two models. The course's Phong model (the
// fields down to `bump_texture`; course scenes and OBJ's Kd/Ks/Ns), or glTF's
// physically based metallic-roughness model (`pbr`; glTF files and OBJ's PBR
// extension), which reads of the fields above it only `double_sided`,
// `two_sided_lighting` and `unlit`. Colours are linear RGB.
struct Material {
  enum class Model : uint8_t { phong, metallic_roughness };
  std::string name;
  Model model = Model::phong;
  vec3 diffuse{1.f};
  vec3 specular{0.f};
  float shininess = 0.f;  // Phong exponent
  // false: no Phong highlight; `specular` only weights reflection and
  // refraction (the course's a5 dialect, which reads shininess and ignores it).
  bool specular_highlight = true;
  vec3 emission{0.f};
  int diffuse_texture = invalid;   // where the hit has uvs: K = diffuse x texel, or the texel alone (below)
  bool texture_modulates = false;  // true: K = diffuse * texel (assets); false: K = texel (course)
  UvTransform uv_transform;
  float alpha_cutoff = -1.f;  // < 0: opaque; else texel alpha below it is a hole
  // false: back faces (seen against the winding's normal) are culled for
  // camera and secondary rays, as glTF's doubleSided=false; shadows still fall.
  bool double_sided = true;
  // true: a back face (seen against the winding's normal) is shaded with its
  // normal reversed, towards the viewer (glTF doubleSided, OBJ); false: with
  // the normal as given (the course format, whose reference does not flip).
  // Refractive materials keep their normals: inside and outside matter there.
  bool two_sided_lighting = false;
  // > 0: refractive, Schlick-weighted reflection and refraction into a medium
  // of this index (rays carry the index of the medium they travel in, 1 for
  // camera rays); 0: opaque (mirror reflection weighted by `specular`).
  float refraction_index = 0.f;
  // false: a shadow ray whose closest hit is this material's surface seen from
  // behind (normal . direction to the light >= 0) does not block the light
  // (the course's a5 rule: only the closest hit before the light counts, and
  // only if it faces the shaded point). true: any surface on the way blocks.
  bool back_faces_cast_shadows = true;
  SolidNoise noise;            // enabled: replaces the diffuse colour in the diffuse term
  bool unlit = false;          // true: the colour is K alone, no lights (glTF KHR_materials_unlit)
  int bump_texture = invalid;  // parsed and kept (course 2019 `bump`)
  PbrMaterial pbr;             // Model::metallic_roughness
};

struct Sphere {
  vec3 center{0.f};
  float radius = 1.f;
};

// The plane normal . p = offset. Readers store a unit normal (the course
// reader divides the written normal and offset by the normal's length); the
// intersection and the writers do not depend on it being unit.
struct Plane {
  vec3 normal{0.f, 1.f, 0.f};
  float offset = 0.f;
};

// A standalone triangle: shaded with its face normal.
struct Triangle {
  std::array<vec3, 3> vertices{};
};

// Triangle mesh with per-vertex attributes (each optional but positions).
struct Mesh {
  std::string name;
  std::string source_path;  // file it was read from, if any
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // empty: face normals
  std::vector<vec2> uvs;      // empty: no texture coordinates (glTF TEXCOORD_0)
  std::vector<vec2> uvs1;     // a second set (glTF TEXCOORD_1), empty or one per position
  // Tangents (xyz, unit, in object space) and the bitangent's sign w (+-1):
  // bitangent = w cross(normal, tangent). Empty: generated where a normal
  // texture needs them (render/prepare).
  std::vector<vec4> tangents;
  std::vector<vec3> colors;         // empty: no vertex colours
  std::vector<uint32_t> indices;    // three per triangle
  std::vector<int> face_materials;  // empty: the node's material for every face
  size_t triangle_count() const { return indices.size() / 3; }
};

enum class ShapeKind : uint8_t { sphere, plane, triangle, mesh };

// Deepest node hierarchy a Scene may hold (root = depth 1). Readers refuse
// deeper files with an error and every walk of the tree relies on it, so that
// recursion stays far from the stack's limit (also under AddressSanitizer).
// Real assets stay below a few dozen levels.
inline constexpr int max_node_depth = 256;

// Node of the scene graph. A group holds children; a transform holds children
// under `local` (object to parent); a shape node references one primitive and
// the material in force when it was declared.
struct Node {
  enum class Kind : uint8_t { group, transform, shape };
  std::string name;
  Kind kind = Kind::group;
  mat4 local{1.f};
  std::vector<int> children;
  ShapeKind shape_kind = ShapeKind::mesh;
  int shape = invalid;     // index into the array of shape_kind
  int material = invalid;  // invalid: the default material
};

// Light arriving from far away in every direction (image-based lighting):
// an equirectangular radiance map in linear RGB, +Y up, direction d at
// u = 0.5 + atan2(d.z, d.x) / 2 pi (mod 1, from the left), v = acos(d.y /
// |d|) / pi (from the top), turned by `rotation_deg` about +Y; or the
// studio the program makes (render/environment_map.h). It lights the
// metallic-roughness materials and is what rays that leave the scene see.
struct Environment {
  enum class Source : uint8_t { none, file, studio };
  Source source = Source::none;
  std::string path;          // Source::file: an EXR, HDR or PFM picture
  float intensity = 1.f;     // radiance scale
  float rotation_deg = 0.f;  // about +Y, counter-clockwise seen from above
};

// Background colour or, when cube_map[0] is valid, a cube map (texture handles
// of the faces in the order right (+x), left (-x), up (+y), down (-y),
// front (+z), back (-z): the course's file names).
struct Background {
  vec3 color{0.5f};
  vec3 ambient{0.f};
  std::string cube_map_dir;  // as written in the scene
  std::array<int, 6> cube_map{invalid, invalid, invalid, invalid, invalid, invalid};
  // Source::none: rays that leave the scene see `color` (or the cube map).
  // Otherwise they see the environment, and camera rays too unless
  // `color_shown` (a colour asked for, e.g. --background).
  Environment environment;
  bool color_shown = false;
};

struct Scene {
  std::string source_path;
  std::vector<Camera> cameras;
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Sphere> spheres;
  std::vector<Plane> planes;
  std::vector<Triangle> triangles;
  std::vector<Mesh> meshes;
  std::vector<Node> nodes;
  int root = invalid;
  Background background;
};

}  // namespace rayform
