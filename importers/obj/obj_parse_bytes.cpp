#include "rayform/importers/obj/obj_parse_bytes.h"

#include "rayform/base/error.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace rayform::obj {
namespace {

// Puts the fields of a chunk, in order, to a sink: one that counts their
// bytes, then one that copies them.
template <class Sink>
void put_chunk(Sink& w, size_t chunk, const ChunkParse& parse) {
  w.number(chunk);
  w.number(parse.ok ? 1 : 0);
  w.text(parse.error);
  if (!parse.ok) return;
  w.text(parse.warn);
  w.array(parse.attrib.vertices);
  w.array(parse.attrib.normals);
  w.array(parse.attrib.texcoords);
  w.array(parse.attrib.colors);
  w.number(parse.shapes.size());
  for (const tinyobj::shape_t& s : parse.shapes) {
    w.text(s.name);
    w.corners(s.mesh.indices);
    w.runs(s.mesh.num_face_vertices);
    w.runs(s.mesh.material_ids);
    w.runs(s.mesh.smoothing_group_ids);
  }
}

// Puts the fields of a chunk's scan, its lines as where they are.
template <class Sink>
void put_scan(Sink& w, size_t chunk, const ChunkScan& scan) {
  w.number(chunk);
  w.number(scan.supported ? 1 : 0);
  w.number(scan.plain ? 1 : 0);
  for (const Line* l : {&scan.first_mtllib, &scan.last_usemtl, &scan.last_group, &scan.last_smoothing}) {
    w.number(l->at);
    w.number(l->text.size());
  }
  w.array(scan.section_faces);
  w.number(scan.vertex_lines);
  w.array(scan.polygon_vertices_before);
  w.number(scan.faces_read_from);
}

// Whether no corner names a uv or a normal (then a corner is its position index alone).
bool positions_only(const std::vector<tinyobj::index_t>& corners) {
  return std::all_of(corners.begin(), corners.end(),
                     [](const tinyobj::index_t& c) { return c.texcoord_index == -1 && c.normal_index == -1; });
}

// The runs of equal values of v, calling run(value, length) for each.
template <class T, class Run>
void for_each_run(const std::vector<T>& v, Run run) {
  for (size_t i = 0; i < v.size();) {
    size_t j = i + 1;
    while (j < v.size() && v[j] == v[i]) ++j;
    run(v[i], j - i);
    i = j;
  }
}

template <class Derived>
class Sink {
 public:
  void number(uint64_t v) { self().raw(&v, sizeof v); }
  void text(const std::string& s) {
    number(s.size());
    self().raw(s.data(), s.size());
  }
  template <class T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    number(v.size());
    self().raw(v.data(), v.size() * sizeof(T));
  }
  // A face's corners: their position indices alone where no corner names a
  // uv or normal (a mesh of positions only: 4 bytes a corner, not 12).
  void corners(const std::vector<tinyobj::index_t>& v) {
    if (!positions_only(v)) {
      number(0);
      array(v);
      return;
    }
    number(1);
    number(v.size());
    for (const tinyobj::index_t& c : v) self().raw(&c.vertex_index, sizeof c.vertex_index);
  }
  // Per-face values as runs of one value (a section's faces mostly share
  // their material, smoothing group and corner count).
  template <class T>
  void runs(const std::vector<T>& v) {
    size_t n = 0;
    for_each_run(v, [&](const T&, size_t) { ++n; });
    number(n);
    for_each_run(v, [&](const T& value, size_t length) {
      self().raw(&value, sizeof value);
      number(length);
    });
  }

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
};

class Counter : public Sink<Counter> {
 public:
  void raw(const void*, size_t n) { bytes += n; }
  size_t bytes = 0;
};

class Writer : public Sink<Writer> {
 public:
  explicit Writer(std::byte* to) : to_(to) {}
  void raw(const void* data, size_t n) {
    if (n) std::memcpy(to_, data, n);
    to_ += n;
  }

 private:
  std::byte* to_;
};

class Reader {
 public:
  explicit Reader(const std::vector<std::byte>& in, size_t at = 0) : in_(in), at_(at) {}

  bool done() const { return at_ == in_.size(); }
  void raw(void* data, size_t n) {
    if (n > in_.size() - at_) throw Error("shared OBJ parse: the bytes of a part end early (a bug)");
    if (n) std::memcpy(data, in_.data() + at_, n);
    at_ += n;
  }
  uint64_t number() {
    uint64_t v;
    raw(&v, sizeof v);
    return v;
  }
  // A count of items of `size` bytes that the rest of the bytes can hold.
  size_t count(size_t size) {
    const uint64_t n = number();
    if (n > (in_.size() - at_) / size) throw Error("shared OBJ parse: an array runs past the bytes of a part (a bug)");
    return size_t(n);
  }
  std::string text() {
    std::string s(count(1), '\0');
    raw(s.data(), s.size());
    return s;
  }
  template <class T>
  void array(std::vector<T>* v) {
    v->resize(count(sizeof(T)));
    raw(v->data(), v->size() * sizeof(T));
  }
  void corners(std::vector<tinyobj::index_t>* v) {
    const uint64_t positions = number();
    if (positions > 1) throw Error("shared OBJ parse: bad corner kind (a bug)");
    if (positions == 0) return array(v);
    v->resize(count(sizeof(int)));
    for (tinyobj::index_t& c : *v) {
      raw(&c.vertex_index, sizeof c.vertex_index);
      c.texcoord_index = c.normal_index = -1;
    }
  }
  const std::byte* here() const { return in_.data() + at_; }
  void skip(size_t n) {
    if (n > in_.size() - at_) throw Error("shared OBJ parse: the bytes of a part end early (a bug)");
    at_ += n;
  }
  // A shape's corners left in the bytes: where they start, how many, and
  // whether as position indices alone.
  void corners_in_place(ShapeBytes* s) {
    const uint64_t positions = number();
    if (positions > 1) throw Error("shared OBJ parse: bad corner kind (a bug)");
    s->positions_only = positions == 1;
    const size_t size = s->positions_only ? sizeof(int) : sizeof(tinyobj::index_t);
    s->corners = count(size);
    s->corner_bytes = here();
    skip(s->corners * size);
  }
  // Runs of T left in the bytes, of `total` values in all (or, with total
  // null, at most `most`, their sum stored there).
  template <class T>
  void runs_in_place(const std::byte** at, size_t* run_count, size_t most, size_t* total) {
    const size_t n = count(sizeof(T) + sizeof(uint64_t));
    *at = here();
    *run_count = n;
    size_t sum = 0;
    for (size_t i = 0; i < n; ++i) {
      skip(sizeof(T));
      const uint64_t length = number();
      if (length > most - sum) throw Error("shared OBJ parse: more faces than corners (a bug)");
      sum += size_t(length);
    }
    *total = sum;
  }
  // Runs of at most `most` values in all.
  template <class T>
  void runs(std::vector<T>* v, size_t most) {
    const size_t n = count(sizeof(T) + sizeof(uint64_t));
    v->clear();
    for (size_t i = 0; i < n; ++i) {
      T value;
      raw(&value, sizeof value);
      const uint64_t length = number();
      if (length > most - v->size()) throw Error("shared OBJ parse: more faces than corners (a bug)");
      v->insert(v->end(), size_t(length), value);
    }
  }

 private:
  const std::vector<std::byte>& in_;
  size_t at_ = 0;
};

}  // namespace

size_t chunk_bytes_size(const ChunkParse& parse) {
  Counter c;
  put_chunk(c, 0, parse);
  return c.bytes;
}

void append_chunk_bytes(size_t chunk, const ChunkParse& parse, std::vector<std::byte>* bytes) {
  const size_t at = bytes->size();
  bytes->resize(at + chunk_bytes_size(parse));
  Writer w(bytes->data() + at);
  put_chunk(w, chunk, parse);
}

std::vector<size_t> read_chunk_bytes(const std::vector<std::byte>& bytes, std::vector<ChunkParse>* chunks,
                                     bool in_place) {
  std::vector<size_t> read;
  Reader r(bytes);
  while (!r.done()) {
    const uint64_t chunk = r.number();
    if (chunk >= chunks->size())
      throw Error("shared OBJ parse: chunk " + std::to_string(chunk) + " of " + std::to_string(chunks->size()) +
                  " (a bug)");
    ChunkParse& p = (*chunks)[chunk];
    p = ChunkParse{};
    p.ok = r.number() != 0;
    p.error = r.text();
    read.push_back(size_t(chunk));
    if (!p.ok) continue;
    p.warn = r.text();
    r.array(&p.attrib.vertices);
    r.array(&p.attrib.normals);
    r.array(&p.attrib.texcoords);
    r.array(&p.attrib.colors);
    p.shapes.resize(r.count(6 * sizeof(uint64_t)));  // a shape takes at least its six sizes
    if (in_place) p.shape_bytes.resize(p.shapes.size());
    for (size_t i = 0; i < p.shapes.size(); ++i) {
      tinyobj::shape_t& s = p.shapes[i];
      s.name = r.text();
      if (in_place) {
        ShapeBytes& b = p.shape_bytes[i];
        r.corners_in_place(&b);
        size_t faces = 0;
        r.runs_in_place<unsigned char>(&b.face_corner_runs, &b.face_corner_run_count, b.corners, &b.faces);
        r.runs_in_place<int>(&b.material_runs, &b.material_run_count, b.faces, &faces);
        if (faces != b.faces) throw Error("shared OBJ parse: a shape's face arrays differ in length (a bug)");
        r.runs_in_place<unsigned int>(&b.smoothing_runs, &b.smoothing_run_count, b.faces, &faces);
        if (faces != b.faces) throw Error("shared OBJ parse: a shape's face arrays differ in length (a bug)");
        continue;
      }
      r.corners(&s.mesh.indices);
      const size_t faces_at_most = s.mesh.indices.size();
      r.runs(&s.mesh.num_face_vertices, faces_at_most);
      r.runs(&s.mesh.material_ids, faces_at_most);
      r.runs(&s.mesh.smoothing_group_ids, faces_at_most);
    }
  }
  return read;
}

namespace {

// Runs of (T, uint64 length) at `at` written out to `to`.
template <class T>
void write_runs(const std::byte* at, size_t runs, T* to) {
  for (size_t i = 0; i < runs; ++i) {
    T value;
    uint64_t length;
    std::memcpy(&value, at, sizeof value);
    std::memcpy(&length, at + sizeof value, sizeof length);
    at += sizeof value + sizeof length;
    to = std::fill_n(to, size_t(length), value);
  }
}

}  // namespace

void read_shape_bytes(const ShapeBytes& s, tinyobj::index_t* corners, unsigned char* face_corners, int* materials,
                      unsigned int* smoothing) {
  if (s.positions_only) {
    for (size_t c = 0; c < s.corners; ++c) {
      std::memcpy(&corners[c].vertex_index, s.corner_bytes + c * sizeof(int), sizeof(int));
      corners[c].texcoord_index = corners[c].normal_index = -1;
    }
  } else if (s.corners) {
    std::memcpy(corners, s.corner_bytes, s.corners * sizeof(tinyobj::index_t));
  }
  write_runs(s.face_corner_runs, s.face_corner_run_count, face_corners);
  write_runs(s.material_runs, s.material_run_count, materials);
  write_runs(s.smoothing_runs, s.smoothing_run_count, smoothing);
}

std::vector<std::byte> scan_bytes(const std::vector<size_t>& chunks, const std::vector<ChunkScan>& scans) {
  Counter c;
  for (size_t k : chunks) put_scan(c, k, scans[k]);
  std::vector<std::byte> bytes(1 + c.bytes, std::byte{1});
  Writer w(bytes.data() + 1);
  for (size_t k : chunks) put_scan(w, k, scans[k]);
  return bytes;
}

std::vector<std::byte> failed_scan_bytes(const std::string& what) {
  std::vector<std::byte> bytes(1 + what.size(), std::byte{0});
  if (!what.empty()) std::memcpy(bytes.data() + 1, what.data(), what.size());
  return bytes;
}

bool scan_bytes_ok(const std::vector<std::byte>& bytes, std::string* failure) {
  if (!bytes.empty() && bytes[0] == std::byte{1}) return true;
  if (bytes.size() > 1) failure->assign(reinterpret_cast<const char*>(bytes.data()) + 1, bytes.size() - 1);
  return false;
}

std::vector<size_t> read_scan_bytes(const std::vector<std::byte>& bytes, std::string_view text,
                                    std::vector<ChunkScan>* scans) {
  std::vector<size_t> read;
  if (bytes.empty() || bytes[0] != std::byte{1}) throw Error("shared OBJ parse: not the bytes of scans (a bug)");
  Reader r(bytes, 1);
  while (!r.done()) {
    const uint64_t chunk = r.number();
    if (chunk >= scans->size())
      throw Error("shared OBJ parse: scan of chunk " + std::to_string(chunk) + " of " + std::to_string(scans->size()) +
                  " (a bug)");
    ChunkScan& s = (*scans)[chunk];
    s = ChunkScan{};
    s.supported = r.number() != 0;
    s.plain = r.number() != 0;
    for (Line* l : {&s.first_mtllib, &s.last_usemtl, &s.last_group, &s.last_smoothing}) {
      const uint64_t at = r.number(), size = r.number();
      if (at > text.size() || size > text.size() - at) throw Error("shared OBJ parse: a line past the text (a bug)");
      *l = size ? Line{text.substr(size_t(at), size_t(size)), size_t(at)} : Line{};
    }
    r.array(&s.section_faces);
    if (s.section_faces.empty()) throw Error("shared OBJ parse: a scan without sections (a bug)");
    s.vertex_lines = size_t(r.number());
    r.array(&s.polygon_vertices_before);
    s.faces_read_from = size_t(r.number());
    if (s.faces_read_from != ChunkScan::none && s.faces_read_from > text.size())
      throw Error("shared OBJ parse: faces past the text (a bug)");
    read.push_back(size_t(chunk));
  }
  return read;
}

}  // namespace rayform::obj
