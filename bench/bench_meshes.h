// Shared helpers of the benchmarks: the benchmark meshes (third-party OBJ
// files read from RAYFORM_SHARED, procedural tori), deterministic ray sets,
// an Embree 3 scene over the very same triangles, and the check that our hits
// agree with Embree's before anything is timed.
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/importers/obj/obj_geometry.h"
#include "rayform/scene/procedural_mesh.h"

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rayform::bench {

// ---------------------------------------------------------------- meshes

inline std::string shared_dir() {
  const char* s = std::getenv("RAYFORM_SHARED");
  return s && *s ? std::string(s) : std::string("/work/shared");
}

struct BenchMesh {
  std::string name;
  std::vector<vec3> positions;  // one spare element at the end (Embree reads 16 bytes per vertex)
  std::vector<uint32_t> indices;
  size_t vertex_count() const { return positions.size() - 1; }
  size_t triangle_count() const { return indices.size() / 3; }
  std::span<const vec3> vertex_span() const { return {positions.data(), vertex_count()}; }
  Bounds3 bounds() const {
    Bounds3 b;
    for (size_t i = 0; i < vertex_count(); ++i) b.expand(positions[i]);
    return b;
  }
};

// The names every benchmark file registers, smallest first. get_mesh also
// knows "degenerate1M", which only bvh_build_bench registers.
inline const std::vector<std::string>& mesh_names() {
  static const std::vector<std::string> names = {"bunny", "beast", "torus1M", "torus10M"};
  return names;
}

// The OBJ file of a scanned mesh, under RAYFORM_SHARED; "" for the procedural tori.
inline std::string obj_path(const std::string& name) {
  if (name == "bunny") return shared_dir() + "/assets/obj/stanford-bunny.obj";
  if (name == "beast") return shared_dir() + "/assets/obj/beast.obj";
  return "";
}

// Why a mesh is not available ("" when it is): the OBJ meshes need RAYFORM_SHARED.
inline std::string mesh_unavailable(const std::string& name) {
  std::string path = obj_path(name);
  if (!path.empty() && !std::filesystem::exists(path)) return "skipped: " + path + " not found (set RAYFORM_SHARED)";
  return "";
}

namespace detail {
inline BenchMesh load_mesh(const std::string& name) {
  BenchMesh m;
  m.name = name;
  if (std::string path = obj_path(name); !path.empty()) {
    ObjGeometry g = read_obj_geometry(path);
    m.positions = std::move(g.positions);
    m.indices.reserve(g.corners.size());
    for (const ObjGeometry::Corner& c : g.corners) m.indices.push_back(uint32_t(c.position));
  } else if (name == "degenerate1M") {
    // 1M copies of one triangle (issue 12's hostile file, smaller): no plane
    // separates the centroids. For build benchmarks only (every ray would
    // test every triangle).
    m.positions = {vec3(0.f, 0.f, 0.f), vec3(1.f, 0.f, 0.f), vec3(0.f, 1.f, 0.f)};
    m.indices.resize(3 * size_t(1'000'000));
    for (size_t i = 0; i < m.indices.size(); ++i) m.indices[i] = uint32_t(i % 3);
  } else {
    size_t n = name == "torus1M" ? 1'000'000 : 10'000'000;
    Mesh t = make_bumpy_torus(n, 1);
    m.positions = std::move(t.positions);
    m.indices = std::move(t.indices);
  }
  m.positions.push_back(vec3(0.f));  // padding
  m.positions.shrink_to_fit();
  return m;
}
}  // namespace detail

// Loads (once per process) and returns the mesh; nullptr when unavailable.
inline const BenchMesh* get_mesh(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<BenchMesh>> cache;
  std::lock_guard lock(mutex);
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  if (!mesh_unavailable(name).empty()) return nullptr;
  auto m = std::make_unique<BenchMesh>(detail::load_mesh(name));
  return (cache[name] = std::move(m)).get();
}

// The mesh for a benchmark, or nullptr after marking it skipped with the reason.
inline const BenchMesh* mesh_or_skip(benchmark::State& state, const std::string& name) {
  const BenchMesh* m = get_mesh(name);
  if (!m) state.SkipWithError(mesh_unavailable(name).c_str());
  return m;
}

// ---------------------------------------------------------------- rays

// SplitMix64: tiny, deterministic on every platform (unlike std:: distributions).
struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed) {}
  uint64_t next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  float uniform() { return float(next() >> 40) * (1.f / 16777216.f); }  // [0, 1)
};

// Pinhole camera rays, emitted in 16x16 pixel tiles (the render loop's order).
// The camera looks at the centre of the bounds from above and in front (the
// view shows the torus hole and the bunny's face), framing the middle 60% of
// the bounding sphere so that most rays hit (about half on the torus).
inline std::vector<Ray> camera_rays(const Bounds3& b, int width, int height) {
  vec3 center = b.center();
  float radius = 0.5f * glm::length(b.extent());
  vec3 back = glm::normalize(vec3(0.3f, 0.5f, 1.f));
  float dist = 2.5f * radius;
  vec3 eye = center + dist * back;
  vec3 w = -back, u = glm::normalize(glm::cross(w, vec3(0.f, 1.f, 0.f))), v = glm::cross(u, w);
  float tan_half = 0.6f * std::tan(std::asin(1.f / 2.5f));  // 1.0: the sphere just fits
  std::vector<Ray> rays;
  rays.reserve(size_t(width) * height);
  const int ts = 16;
  for (int ty = 0; ty < height; ty += ts)
    for (int tx = 0; tx < width; tx += ts)
      for (int y = ty; y < std::min(height, ty + ts); ++y)
        for (int x = tx; x < std::min(width, tx + ts); ++x) {
          float px = (2.f * (x + 0.5f) / width - 1.f) * tan_half;
          float py = (1.f - 2.f * (y + 0.5f) / height) * tan_half;
          Ray r;
          r.origin = eye;
          r.direction = glm::normalize(px * u + py * v + w);
          rays.push_back(r);
        }
  return rays;
}

// Incoherent rays: origins uniform in the bounding box, directions uniform on
// the sphere (deterministic for a seed).
inline std::vector<Ray> random_rays(const Bounds3& b, size_t count, uint64_t seed) {
  Rng rng(seed);
  std::vector<Ray> rays(count);
  vec3 e = b.extent();
  for (Ray& r : rays) {
    r.origin = b.lo + vec3(rng.uniform() * e.x, rng.uniform() * e.y, rng.uniform() * e.z);
    float z = 1.f - 2.f * rng.uniform(), phi = 6.2831853f * rng.uniform();
    float s = std::sqrt(std::max(0.f, 1.f - z * z));
    r.direction = vec3(s * std::cos(phi), s * std::sin(phi), z);
  }
  return rays;
}

inline constexpr int camera_width = 1024, camera_height = 1024;
inline constexpr size_t random_ray_count = size_t(1) << 19;
inline constexpr uint64_t random_seed = 20240611;

inline std::vector<Ray> make_rays(const BenchMesh& m, const std::string& kind) {
  return kind == "camera" ? camera_rays(m.bounds(), camera_width, camera_height)
                          : random_rays(m.bounds(), random_ray_count, random_seed);
}

// ---------------------------------------------------------------- Embree

// Bytes Embree holds, through the device's memory monitor.
struct EmbreeMemory {
  std::atomic<int64_t> current{0}, peak{0};
  void reset_peak() { peak = current.load(); }
};

inline bool embree_memory_monitor(void* user, ssize_t bytes, bool /*post*/) {
  auto* m = static_cast<EmbreeMemory*>(user);
  int64_t now = (m->current += bytes);
  int64_t p = m->peak.load();
  while (now > p && !m->peak.compare_exchange_weak(p, now)) {
  }
  return true;
}

// One device per process (all hardware threads), with its memory monitor.
struct EmbreeDevice {
  RTCDevice device = nullptr;
  EmbreeMemory memory;
  EmbreeDevice() {
    device = rtcNewDevice(nullptr);
    if (!device) {
      std::fprintf(stderr, "rtcNewDevice failed: %d\n", int(rtcGetDeviceError(nullptr)));
      std::abort();
    }
    rtcSetDeviceMemoryMonitorFunction(device, embree_memory_monitor, &memory);
  }
  ~EmbreeDevice() { rtcReleaseDevice(device); }
};

inline EmbreeDevice& embree_device() {
  static EmbreeDevice d;
  return d;
}

// A committed Embree scene with one triangle geometry sharing the mesh's
// vertex and index buffers (so Embree's own memory is its BVH and leaves).
struct EmbreeScene {
  RTCScene scene = nullptr;
  EmbreeScene() = default;
  EmbreeScene(const BenchMesh& m, RTCBuildQuality quality) {
    RTCDevice dev = embree_device().device;
    scene = rtcNewScene(dev);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, quality);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0, sizeof(vec3),
                               m.vertex_count());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0, 3 * sizeof(uint32_t),
                               m.triangle_count());
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
      std::fprintf(stderr, "Embree error while building %s\n", m.name.c_str());
      std::abort();
    }
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  EmbreeScene(EmbreeScene&& o) noexcept : scene(o.scene) { o.scene = nullptr; }
  EmbreeScene& operator=(EmbreeScene&& o) noexcept {
    std::swap(scene, o.scene);
    return *this;
  }
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
  }
};

inline RTCRayHit to_embree(const Ray& r) {
  RTCRayHit rh;
  rh.ray.org_x = r.origin.x;
  rh.ray.org_y = r.origin.y;
  rh.ray.org_z = r.origin.z;
  rh.ray.dir_x = r.direction.x;
  rh.ray.dir_y = r.direction.y;
  rh.ray.dir_z = r.direction.z;
  rh.ray.tnear = r.tmin;
  rh.ray.tfar = r.tmax;
  rh.ray.time = 0.f;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// ---------------------------------------------------------------- tracing loops

inline double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

inline double wall_seconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Each returns a checksum of what it found, so that nothing is optimised away.
inline double ours_closest(const MeshAccel& m, std::span<const Ray> rays) {
  double sum = 0.;
  for (const Ray& r : rays) {
    float t = r.tmax;
    MeshHit h;
    if (intersect_mesh(m, r, t, &h)) sum += double(t) + double(h.triangle & 7);
  }
  return sum;
}

// The same, eight consecutive rays at a time (intersect_mesh8; camera rays
// are in rows, so eight neighbouring pixels of a row).
inline double ours_closest8(const MeshAccel& m, std::span<const Ray> rays) {
  double sum = 0.;
  Ray group[8];
  for (size_t i = 0; i < rays.size(); i += 8) {
    const int n = int(std::min<size_t>(8, rays.size() - i));
    float t[8];
    MeshHit h[8];
    for (int k = 0; k < 8; ++k) {
      group[k] = rays[i + size_t(std::min(k, n - 1))];
      t[k] = group[k].tmax;
    }
    const int found = intersect_mesh8(m, group, (1 << n) - 1, t, h);
    for (int k = 0; k < n; ++k)
      if ((found >> k) & 1) sum += double(t[k]) + double(h[k].triangle & 7);
  }
  return sum;
}

inline double embree_closest(RTCScene scene, std::span<const Ray> rays) {
  double sum = 0.;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (const Ray& r : rays) {
    RTCRayHit rh = to_embree(r);
    rtcIntersect1(scene, &ctx, &rh);
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) sum += double(rh.ray.tfar) + double(rh.hit.primID & 7);
  }
  return sum;
}

inline size_t ours_any(const MeshAccel& m, std::span<const Ray> rays) {
  size_t n = 0;
  for (const Ray& r : rays) n += occluded_mesh(m, r);
  return n;
}

inline size_t embree_any(RTCScene scene, std::span<const Ray> rays) {
  size_t n = 0;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (const Ray& r : rays) {
    RTCRay ray = to_embree(r).ray;
    rtcOccluded1(scene, &ctx, &ray);
    n += ray.tfar < 0.f;  // Embree sets tfar to -inf on a hit
  }
  return n;
}

// ---------------------------------------------------------------- verification

struct Agreement {
  size_t closest_mismatches = 0;  // hit/miss differ, or t differs by more than 1e-4 relative
  size_t any_mismatches = 0;      // occluded differs
  size_t hits = 0;                // rays Embree reports a hit for
};

// Traces every ray with both and counts disagreements.
inline Agreement compare_with_embree(const MeshAccel& ours, RTCScene embree, std::span<const Ray> rays) {
  Agreement a;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (const Ray& r : rays) {
    float t = r.tmax;
    MeshHit h;
    bool ours_hit = intersect_mesh(ours, r, t, &h);
    RTCRayHit rh = to_embree(r);
    rtcIntersect1(embree, &ctx, &rh);
    bool emb_hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    a.hits += emb_hit;
    if (ours_hit != emb_hit ||
        (ours_hit && std::abs(t - rh.ray.tfar) > 1e-4f * std::max(std::abs(t), std::abs(rh.ray.tfar))))
      ++a.closest_mismatches;
    RTCRay ray = to_embree(r).ray;
    rtcOccluded1(embree, &ctx, &ray);
    if (occluded_mesh(ours, r) != (ray.tfar < 0.f)) ++a.any_mismatches;
  }
  return a;
}

}  // namespace rayform::bench
