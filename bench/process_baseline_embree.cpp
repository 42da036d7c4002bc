// The baseline of scripts/bench-process: what a user writes with Embree 3 to
// render an OBJ file, as a whole program (no rayform code). tinyobjloader reads
// the file; one triangle geometry shares its vertex and index buffers; one
// camera ray per pixel with rtcIntersect1, in rows handed out by oneTBB;
// shading = max(0, N.L), N the geometric normal turned towards the viewer and
// L the direction towards the camera (a head-light), background 0; the picture
// is written as a 24-bit BMP (to a temporary name, then renamed).
//
// usage: rayform_process_baseline MESH.obj WIDTHxHEIGHT THREADS EYE_X,EYE_Y,EYE_Z AT_X,AT_Y,AT_Z FOV_DEGREES OUT.bmp
//   up is +Y; FOV = vertical opening angle; THREADS 0 = all hardware threads.
// Prints "stats: load L s, build B s, render R s, write W s" on stderr (steady_clock).
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

struct V3 {
  float x, y, z;
};
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(float s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
float dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 normalize(V3 a) { return (1.f / std::sqrt(dot(a, a))) * a; }

V3 parse_v3(const char* s) {
  V3 v;
  if (std::sscanf(s, "%f,%f,%f", &v.x, &v.y, &v.z) != 3) throw std::runtime_error(std::string("not X,Y,Z: ") + s);
  return v;
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// 24-bit BMP, rows bottom to top, each padded to 4 bytes; `bgr` holds the rows
// in that order without padding.
void write_bmp(const std::string& path, int w, int h, const std::vector<uint8_t>& bgr) {
  const uint32_t row = (uint32_t(w) * 3 + 3) & ~3u, data = row * uint32_t(h);
  uint8_t head[54] = {'B', 'M'};
  auto put32 = [&](int at, uint32_t v) {
    for (int k = 0; k < 4; ++k) head[at + k] = uint8_t(v >> (8 * k));
  };
  put32(2, 54 + data);  // file size
  put32(10, 54);        // offset of the pixels
  put32(14, 40);        // BITMAPINFOHEADER
  put32(18, uint32_t(w));
  put32(22, uint32_t(h));
  head[26] = 1;   // planes
  head[28] = 24;  // bits per pixel
  put32(34, data);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f.write(reinterpret_cast<const char*>(head), sizeof head);
    const char pad[3] = {};
    for (int y = 0; y < h; ++y) {
      f.write(reinterpret_cast<const char*>(bgr.data()) + size_t(y) * size_t(w) * 3, std::streamsize(w) * 3);
      f.write(pad, std::streamsize(row - uint32_t(w) * 3));
    }
    if (!f.flush()) throw std::runtime_error(tmp + ": cannot write");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc != 8) {
      std::fprintf(stderr,
                   "usage: rayform_process_baseline MESH.obj WIDTHxHEIGHT THREADS EYE_X,EYE_Y,EYE_Z AT_X,AT_Y,AT_Z "
                   "FOV_DEGREES OUT.bmp\n");
      return 2;
    }
    int width = 0, height = 0;
    if (std::sscanf(argv[2], "%dx%d", &width, &height) != 2 || width < 1 || height < 1)
      throw std::runtime_error(std::string("not WIDTHxHEIGHT: ") + argv[2]);
    int threads = std::atoi(argv[3]);
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const V3 eye = parse_v3(argv[4]), at = parse_v3(argv[5]);
    const float fov = std::strtof(argv[6], nullptr);
    const std::string out = argv[7];
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

    // Load: positions (plus one float of padding: Embree reads 16 bytes per vertex) and indices.
    double t0 = now();
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, argv[1], nullptr, true, false))
      throw std::runtime_error(std::string(argv[1]) + ": " + err);
    std::vector<float>& positions = attrib.vertices;
    const size_t vertex_count = positions.size() / 3;
    positions.push_back(0.f);
    std::vector<uint32_t> indices;
    for (const tinyobj::shape_t& s : shapes)
      for (const tinyobj::index_t& ix : s.mesh.indices) indices.push_back(uint32_t(ix.vertex_index));
    const size_t triangle_count = indices.size() / 3;

    // Build.
    double t1 = now();
    const std::string config = "threads=" + std::to_string(threads);
    RTCDevice device = rtcNewDevice(config.c_str());
    if (!device) throw std::runtime_error("rtcNewDevice failed");
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions.data(), 0,
                               3 * sizeof(float), vertex_count);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices.data(), 0,
                               3 * sizeof(uint32_t), triangle_count);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("Embree error while building");

    // Render: pinhole camera, rays through pixel centres, rows bottom to top (BMP order).
    double t2 = now();
    const V3 w = normalize(at - eye), u = normalize(cross(w, V3{0.f, 1.f, 0.f})), v = cross(u, w);
    const float half_h = std::tan(fov * 3.14159265f / 360.f), half_w = half_h * float(width) / float(height);
    std::vector<uint8_t> bgr(size_t(width) * size_t(height) * 3);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      for (int y = rows.begin(); y < rows.end(); ++y) {
        const float sy = (2.f * (float(y) + 0.5f) / float(height) - 1.f) * half_h;
        for (int x = 0; x < width; ++x) {
          const float sx = (2.f * (float(x) + 0.5f) / float(width) - 1.f) * half_w;
          const V3 d = normalize(w + sx * u + sy * v);
          RTCRayHit rh;
          rh.ray.org_x = eye.x;
          rh.ray.org_y = eye.y;
          rh.ray.org_z = eye.z;
          rh.ray.dir_x = d.x;
          rh.ray.dir_y = d.y;
          rh.ray.dir_z = d.z;
          rh.ray.tnear = 0.f;
          rh.ray.tfar = INFINITY;
          rh.ray.time = 0.f;
          rh.ray.mask = ~0u;
          rh.ray.id = 0;
          rh.ray.flags = 0;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(scene, &ctx, &rh);
          float shade = 0.f;
          if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            V3 n = normalize(V3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
            if (dot(n, d) > 0.f) n = -1.f * n;  // towards the viewer
            shade = std::max(0.f, -dot(n, d));  // L = -d: towards the camera
          }
          const uint8_t g = uint8_t(std::min(255.f, shade * 255.f + 0.5f));
          uint8_t* p = &bgr[(size_t(y) * size_t(width) + size_t(x)) * 3];
          p[0] = p[1] = p[2] = g;
        }
      }
    });

    double t3 = now();
    write_bmp(out, width, height, bgr);
    double t4 = now();
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    std::fprintf(stderr, "stats: load %.4f s, build %.4f s, render %.4f s, write %.4f s (%zu triangles, %d threads)\n",
                 t1 - t0, t2 - t1, t3 - t2, t4 - t3, triangle_count, threads);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rayform_process_baseline: %s\n", e.what());
    return 1;
  }
}
