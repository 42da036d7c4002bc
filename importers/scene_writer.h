// One entry point over the format writers: a Scene to course .txt, OBJ+MTL or
// glTF/GLB, picked by the output's extension (see docs/convert.md).
//
// Writers never lose anything silently: whatever the target format cannot
// hold (a camera in OBJ, a point light's falloff in the 2012 course dialect,
// a sphere that has to become triangles, ...) is reported as one message,
// naming the output file.
//
// Below the entry point: the helpers the three writers share (tessellation,
// flattening, texture images, numbers, atomic file output).
#pragma once

#include "course_txt/course_reader.h"
#include "geometry/bounds.h"
#include "scene/scene.h"

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace rayform {

struct SaveOptions {
  // Bake every transform into the geometry: one flat group of shapes in world
  // space (spheres stay spheres under rotations, translations and uniform
  // scales; under other transforms they are tessellated).
  bool flatten = false;
  // glTF: buffers and images inside the .gltf as data URIs (a .glb always
  // holds them in its binary chunk).
  bool embed = false;
  // Longitudes of a tessellated sphere (>= 3); it has segments / 2 bands.
  int sphere_segments = 64;
  // Course output: the dialect to write; unset: 2012 unless the scene needs
  // 2019 (falloff, bump maps, a raw camera up vector, 2019 mesh normals).
  std::optional<CourseDialect> dialect;
  // glTF: keep spheres, planes and triangles' analytic form in primitive
  // extras (rayform's reader restores them). false: meshes only, so every
  // reader, rayform's included, sees the tessellation.
  bool shape_extras = true;
};

struct SaveResult {
  std::vector<std::string> files;  // every file written, the main one first
  size_t stored_triangles = 0;     // triangles stored in the written meshes (instances count once)
};

// Writes `scene` to `path` (.txt, .obj, .gltf, .glb). Messages about what the
// target cannot hold are appended to `messages` (if given), each starting with
// the output's name. Throws rayform::Error naming the file on failure; files
// are written to temporary names and renamed into place, so a failure leaves
// no partial file.
SaveResult save_scene(const Scene& scene, const std::string& path, const SaveOptions& options = {},
                      std::vector<std::string>* messages = nullptr);

// ---- shared by the writers ------------------------------------------------------

// A UV sphere of `segments` longitudes and max(2, segments / 2) bands: two pole
// vertices and (bands - 1) rings of `segments` vertices on the sphere, unit
// outward normals (p - c) / r, no uvs; 2 segments (bands - 1) triangles, none
// degenerate, counter-clockwise seen from outside.
Mesh tessellate_sphere(const Sphere& sphere, int segments);

// The plane as a square of two triangles with half-size `half_size`, centred on
// the point of the plane nearest `around`, facing the plane's normal.
Mesh plane_quad(const Plane& plane, vec3 around, float half_size);

// Where a plane's quad goes: the bounds of everything bounded in the scene
// (shapes, camera centres, light positions), world space; empty for a scene of
// planes alone. The quad's half-size is plane_quad_scale times the radius of
// these bounds (at least 1), so that it reaches the horizon to within a pixel
// for any camera inside them.
Bounds3 scene_extent(const Scene& scene);
inline constexpr float plane_quad_scale = 1000.f;

// The scene with every transform baked into the shapes: root group -> one shape
// node per instance, identity matrices, meshes copied per instance (normals by
// the inverse transpose, winding reversed under mirroring). Messages for spheres
// that had to be tessellated. `name` prefixes the messages.
Scene flatten_scene(const Scene& scene, int sphere_segments, const std::string& name,
                    std::vector<std::string>* messages);

// A mesh under an object-to-world matrix: positions transformed, normals by
// the inverse transpose (renormalised), winding reversed when m mirrors.
Mesh transform_mesh(const Mesh& mesh, const mat4& m);
// The plane n . p = d under m (unit normal in the result).
Plane transform_plane(const Plane& plane, const mat4& m);

// Mesh counts over the scene's meshes (each once).
struct MeshTotals {
  size_t vertices = 0, uvs = 0, normals = 0, triangles = 0;
};
MeshTotals mesh_totals(const Scene& scene);

// Shortest decimal text that reads back as the same float ("0.9", "-2", "1e-07").
std::string format_float(float v);
// The three components by format_float, separated by spaces ("0.5 1 -2").
std::string format_vec3(vec3 v);
// Names quoted and joined for messages: 'a', 'b', 'c'.
std::string quoted_list(const std::set<std::string>& names);

// A file name made of [A-Za-z0-9._-] only (others become '_'), never empty.
std::string safe_file_name(const std::string& name);

// A texture's name for files: the stem of its name (or file), '\\' read as a
// separator (".\\wal67ar_small.jpg" -> "wal67ar_small").
std::string texture_base_name(const Texture& texture);

// Decoded 8-bit pixels, row 0 at the top.
struct Pixels8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> data;
};

// The texture's pixels: Texture::pixels, or its file decoded. Throws rayform::Error.
Pixels8 texture_pixels(const Texture& texture);

// The texture as a file of one of the `wanted` formats (lower-case extensions
// without the dot: "png", "jpg", "bmp"): its own file's bytes when that file
// has one of them (no re-encoding), else its pixels encoded as wanted[0]
// (png or bmp; bmp drops alpha). `ext` receives the extension used.
std::vector<uint8_t> texture_file(const Texture& texture, const std::vector<std::string>& wanted, std::string* ext);

// PNG / BMP encoding of 8-bit pixels (BMP: 3 channels, alpha dropped).
std::vector<uint8_t> encode_png(const Pixels8& p);
std::vector<uint8_t> encode_bmp(const Pixels8& p);

std::vector<uint8_t> read_file_bytes(const std::string& path);

// A set of output files committed together: each is written to a temporary
// name in its final folder, then all are renamed into place, the main file
// last. On failure nothing is renamed and the temporaries are removed.
class OutputFiles {
 public:
  // `main` is written last; its folder must exist.
  explicit OutputFiles(std::string main);
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  const std::string& main() const { return main_; }
  // A path for `file_name` beside the main file.
  std::string beside(const std::string& file_name) const;
  // Content of a file (a later add of the same path replaces it).
  void add(const std::string& path, std::vector<uint8_t> bytes);
  void add(const std::string& path, const std::string& text);
  // A file already written at `temp_path` (on the same file system) that
  // becomes `path` at commit; removed with the other temporaries when the
  // set is not committed.
  void add_written(const std::string& path, const std::string& temp_path);
  bool has(const std::string& path) const;
  // A fresh temporary folder beside the main file, removed by the destructor.
  std::string temp_dir();
  // Writes and renames everything; returns the final paths, main first.
  std::vector<std::string> commit();

 private:
  struct Entry {
    std::string path;
    std::vector<uint8_t> bytes;
    std::string temp;  // non-empty: already written there
  };
  std::string main_;
  std::vector<Entry> entries_;
  std::vector<std::string> temps_, temp_dirs_;
};

}  // namespace rayform
