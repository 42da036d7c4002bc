// read_obj_geometry through the chunked parallel parse gives exactly the
// ObjGeometry of the one-piece tinyobj::ObjReader::ParseFromFile it made
// before (a copy of that reader is the reference here): the same arrays bit
// for bit, the same corners in the same order, the same warnings and errors.
// And read_course_mesh's vertex split by (position, uv) numbers vertices as
// the std::map split it replaces did (first met in corner order), with the
// course's normals summed per position in the same order. Over the
// shared OBJ assets, the course meshes and made-up files, cut in chunks of
// several sizes.
#include "rayform/importers/course_txt/course_mesh.h"
#include "rayform/importers/obj/obj_geometry.h"
#include "rayform/base/error.h"
#include "importers/obj_test_texts.h"
#include "test_importers.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;
using test::same_bits;

// read_obj_geometry as it was before the chunked parse (a verbatim copy).
ObjGeometry reference_geometry(const std::string& path) {
  {
    std::ifstream probe(path);
    if (!probe) throw Error(path + ": cannot open OBJ file");
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string e = reader.Error();
    while (!e.empty() && e.back() == '\n') e.pop_back();
    throw Error(path + ": cannot read OBJ: " + e);
  }
  const tinyobj::attrib_t& a = reader.GetAttrib();
  ObjGeometry g;
  g.positions.resize(a.vertices.size() / 3);
  for (size_t i = 0; i < g.positions.size(); ++i) {
    g.positions[i] = vec3(a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]);
    if (!is_finite(g.positions[i]))
      throw Error(path + ": vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
  }
  g.normals.resize(a.normals.size() / 3);
  for (size_t i = 0; i < g.normals.size(); ++i)
    g.normals[i] = vec3(a.normals[3 * i], a.normals[3 * i + 1], a.normals[3 * i + 2]);
  g.uvs.resize(a.texcoords.size() / 2);
  for (size_t i = 0; i < g.uvs.size(); ++i) g.uvs[i] = vec2(a.texcoords[2 * i], a.texcoords[2 * i + 1]);
  auto check = [&](int index, size_t count, const char* what) {
    if (index >= int(count) || index < -1)
      throw Error(path + ": face refers to " + what + " " + std::to_string(index + 1) + " but the file has " +
                  std::to_string(count));
  };
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (unsigned char fv : shape.mesh.num_face_vertices) {
      if (fv == 3) {
        for (int k = 0; k < 3; ++k) {
          const tinyobj::index_t& ix = shape.mesh.indices[offset + k];
          check(ix.vertex_index, g.positions.size(), "vertex");
          check(ix.normal_index, g.normals.size(), "normal");
          check(ix.texcoord_index, g.uvs.size(), "texture coordinate");
          if (ix.vertex_index < 0) throw Error(path + ": face corner without a vertex index");
          g.corners.push_back({ix.vertex_index, ix.normal_index, ix.texcoord_index});
        }
      }
      offset += fv;
    }
  }
  if (g.corners.empty()) throw Error(path + ": OBJ file has no triangles");
  std::string w = reader.Warning();
  if (!w.empty()) g.warnings.push_back(path + ": " + w);
  return g;
}

// course_position_normals as it was, one loop (a verbatim copy).
std::vector<vec3> reference_position_normals(const std::vector<vec3>& positions, const std::vector<uint32_t>& corners,
                                             CourseDialect dialect) {
  std::vector<vec3> sum(positions.size(), vec3(0.f));
  for (size_t c = 0; c + 2 < corners.size(); c += 3) {
    const uint32_t i0 = corners[c], i1 = corners[c + 1], i2 = corners[c + 2];
    vec3 n = glm::cross(positions[i1] - positions[i0], positions[i2] - positions[i0]);
    if (dialect == CourseDialect::v2019) {
      const float len = glm::length(n);
      if (!(len > 0.f)) continue;
      n /= len;
    }
    sum[i0] += n;
    sum[i1] += n;
    sum[i2] += n;
  }
  for (vec3& n : sum) {
    const float len = glm::length(n);
    n = len > 0.f ? n / len : vec3(0.f);
  }
  return sum;
}

// read_course_mesh's vertices as the std::map split made them, from `g`.
Mesh reference_course_mesh(const std::string& path, const ObjGeometry& g, CourseDialect dialect) {
  std::vector<uint32_t> corners;
  for (const auto& c : g.corners) corners.push_back(uint32_t(c.position));
  const std::vector<vec3> position_normals = reference_position_normals(g.positions, corners, dialect);
  Mesh m;
  m.source_path = path;
  const bool flat = dialect == CourseDialect::a5 && g.positions.size() <= course_a5_flat_mesh_vertices;
  bool has_uv = false;
  for (const auto& c : g.corners) has_uv |= c.uv >= 0;
  if (!has_uv) {
    m.positions = g.positions;
    if (!flat) m.normals = position_normals;
    for (const auto& c : g.corners) m.indices.push_back(uint32_t(c.position));
    return m;
  }
  std::map<std::pair<int, int>, uint32_t> split;
  for (const auto& c : g.corners) {
    auto [it, inserted] = split.try_emplace({c.position, c.uv}, uint32_t(m.positions.size()));
    if (inserted) {
      m.positions.push_back(g.positions[c.position]);
      if (!flat) m.normals.push_back(position_normals[c.position]);
      m.uvs.push_back(c.uv >= 0 ? g.uvs[c.uv] : vec2(0.f));
    }
    m.indices.push_back(it->second);
  }
  return m;
}

// Where two geometries differ, or "" when they agree bit for bit.
std::string difference(const ObjGeometry& a, const ObjGeometry& b) {
  if (!same_bits(a.positions, b.positions)) return "positions";
  if (!same_bits(a.normals, b.normals)) return "normals";
  if (!same_bits(a.uvs, b.uvs)) return "uvs";
  if (a.corners.size() != b.corners.size())
    return "corner count " + std::to_string(a.corners.size()) + " vs " + std::to_string(b.corners.size());
  for (size_t c = 0; c < a.corners.size(); ++c) {
    const ObjGeometry::Corner &x = a.corners[c], &y = b.corners[c];
    if (x.position != y.position || x.normal != y.normal || x.uv != y.uv) return "corner " + std::to_string(c);
  }
  if (a.warnings != b.warnings) return "warnings";
  return "";
}

std::string difference(const Mesh& a, const Mesh& b) {
  if (!same_bits(a.positions, b.positions)) return "positions";
  if (!same_bits(a.normals, b.normals)) return "normals";
  if (!same_bits(a.uvs, b.uvs)) return "uvs";
  if (a.indices != b.indices) return "indices";
  if (a.source_path != b.source_path) return "source path";
  return "";
}

// What reading `path` gives: the geometry, or the error's message.
struct Result {
  ObjGeometry geometry;
  std::string error;
};
template <class Read>
Result attempt(const Read& read) {
  Result r;
  try {
    r.geometry = read();
  } catch (const Error& e) {
    r.error = e.what();
  }
  return r;
}

// The chunk sizes each file is read with: in one piece, tiny chunks (state
// lines at chunk ends), middling ones, and the reader's own choice.
constexpr size_t chunk_sizes[] = {ObjGeometryOptions::serial, 0, 37, 200, 4096, 65536};

void expect_same_as_reference(const fs::path& file) {
  SCOPED_TRACE(file.string());
  const Result want = attempt([&] { return reference_geometry(file.string()); });
  for (size_t chunk : chunk_sizes) {
    ObjGeometryOptions o;
    o.parse_chunk_bytes = chunk;
    const Result got = attempt([&] { return read_obj_geometry(file.string(), o); });
    EXPECT_EQ(got.error, want.error) << "chunks of " << chunk << " bytes";
    EXPECT_EQ(difference(got.geometry, want.geometry), "") << "chunks of " << chunk << " bytes";
  }
}

std::vector<fs::path> obj_files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".obj") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

struct TempFiles {
  fs::path dir = test::temp_dir("obj-geometry");
  TempFiles() { fs::create_directories(dir); }
  ~TempFiles() { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
};

TEST(ObjGeometryParallel, TheComparisonSeesACornerOrderChangeAWarningAndABit) {
  TempFiles t;
  const fs::path f = t.write("quads.obj", test::grid_file(6, true));
  const ObjGeometry a = reference_geometry(f.string());
  ASSERT_GE(a.corners.size(), 6u);
  ASSERT_EQ(difference(a, a), "");
  ObjGeometry b = a;
  std::swap(b.corners[1], b.corners[2]);
  EXPECT_EQ(difference(a, b), "corner 1");
  b = a;
  std::rotate(b.corners.begin(), b.corners.begin() + 3, b.corners.end());  // the triangles in another order
  EXPECT_NE(difference(a, b), "");
  b = a;
  b.warnings.clear();
  ASSERT_FALSE(a.warnings.empty());  // the file names a material m.mtl does not have, and no m.mtl
  EXPECT_EQ(difference(a, b), "warnings");
  b = a;
  b.positions[0].x = std::nextafter(b.positions[0].x, 1e9f);
  EXPECT_EQ(difference(a, b), "positions");
}

TEST(ObjGeometryParallel, SharedAssetsAndCourseMeshesAsBefore) {
  std::vector<fs::path> files = obj_files_under(test::shared_dir() / "assets" / "obj");
  const std::vector<fs::path> course = obj_files_under(test::shared_dir() / "course");
  files.insert(files.end(), course.begin(), course.end());
  if (files.empty()) GTEST_SKIP() << "no OBJ files under " << test::shared_dir();
  for (const fs::path& f : files) expect_same_as_reference(f);
}

TEST(ObjGeometryParallel, MadeUpFilesAsBefore) {
  TempFiles t;
  t.write("m.mtl", test::mtl_text);
  std::vector<fs::path> files = {
      t.write("grid.obj", test::grid_file(40, true)),  // every corner style, o/g/usemtl/s, an unknown material
      t.write("grid_plain.obj", test::grid_file(30, false)),
      t.write("polygons.obj", test::polygon_file(20)),  // quads, concave and 255-corner polygons
  };
  {
    // No uvs, no normals, no materials: the chunked parse's own (no warning).
    std::ostringstream s;
    for (int y = 0; y < 60; ++y)
      for (int x = 0; x < 60; ++x) s << "v " << x * 0.5 << " " << y * 0.25 << " " << (x ^ y) * 0.01 << "\n";
    for (int y = 0; y + 1 < 60; ++y)
      for (int x = 0; x + 1 < 60; ++x) {
        const int a = y * 60 + x + 1;
        s << "f " << a << " " << a + 1 << " " << a + 61 << "\nf " << a << " " << a + 61 << " " << a + 60 << "\n";
      }
    files.push_back(t.write("no_uvs.obj", s.str()));
    // Some corners with uvs, some without.
    std::string mixed = s.str() + "vt 0.5 0.5\nvt 0.25 0.75\nf 1/1 2/2 62/1\nf 3 4/2 63\n";
    files.push_back(t.write("some_uvs.obj", mixed));
  }
  {
    // Negative (relative) indices: the chunked parse falls back.
    std::ostringstream s;
    for (int k = 0; k < 200; ++k)
      s << "v " << k << " " << k % 7 << " 0\nv " << k << " 1 " << k % 3 << "\nv " << k + 1 << " 0 1\nvt 0 " << k
        << "\nf -3/-1 -2/-1 -1/-1\n";
    files.push_back(t.write("negative.obj", s.str()));
  }
  {
    // Windows line ends, tabs, a comment, a face past the last vertex, no faces.
    files.push_back(t.write("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\n\tv 0 1 0\r\n# c\r\nf 1 2 3\r\nf 1 3 2\r\n"));
    files.push_back(t.write("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"));
    files.push_back(t.write("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"));
    files.push_back(t.write("bad_uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/1 2/3 3/1\n"));
    files.push_back(
        t.write("bad_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 2//1 3//4\n"));
    files.push_back(t.write("non_finite.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"));
    files.push_back(t.write("missing_mtl.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    files.push_back(t.dir / "does_not_exist.obj");
  }
  for (const fs::path& f : files) expect_same_as_reference(f);
}

TEST(ObjGeometryParallel, CourseMeshSplitAsTheMapSplit) {
  TempFiles t;
  std::vector<fs::path> files = obj_files_under(test::shared_dir() / "course");
  // Over 1 MiB (parsed in chunks): uvs with seams; no uvs.
  for (const char* big : {"obj/beast.obj", "obj/stanford-bunny.obj"})
    if (fs::is_regular_file(test::asset(big))) files.push_back(test::asset(big));
  files.push_back(t.write("grid.obj", test::grid_file(40, true)));
  files.push_back(t.write("polygons.obj", test::polygon_file(20)));
  {
    // A small mesh with uvs: a5 shades it flat.
    files.push_back(t.write("small_uv.obj",
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0.5\n"
                            "f 1/1 2/2 4/4\nf 1/5 4/4 3/3\nf 1 3 2\n"));
  }
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const ObjGeometry g = reference_geometry(f.string());
    for (CourseDialect d : {CourseDialect::v2012, CourseDialect::v2019, CourseDialect::a5}) {
      const Mesh want = reference_course_mesh(f.string(), g, d);
      const Mesh got = read_course_mesh(f.string(), d);
      EXPECT_EQ(difference(got, want), "") << course_dialect_name(d);
    }
  }
}

}  // namespace
}  // namespace rayform
