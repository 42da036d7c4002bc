#include "render/render.h"

#include "render/camera_rays.h"
#include "render/shade_phong.h"
#include "scene/error.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <memory>
#include <mutex>

namespace rayform {
namespace {

struct PixelSample {
  vec3 color{0.f};
  float depth = infinity;
  vec3 normal{0.f};
  vec3 albedo{0.f};
};

struct Tracer {
  const PreparedScene& p;
  const RenderOptions& o;
  const Scene& s;

  vec3 background(const Ray&) const { return s.background.color; }

  // Closest opaque hit: cut-out holes (alpha below the material's cutoff) are skipped.
  bool closest_opaque(Ray ray, Hit* hit, SurfacePoint* sp, vec4* k) const {
    for (;;) {
      if (!intersect_scene(p, ray, hit)) return false;
      *sp = surface_point(p, ray, *hit);
      const Material& m = p.materials[sp->material];
      *k = surface_albedo(p, m, *sp);
      if (!p.features.alpha_cutout || m.alpha_cutoff < 0.f || k->a >= m.alpha_cutoff) return true;
      ray.tmin = next_float_up(hit->t);
    }
  }

  PixelSample trace_camera(const Ray& ray) const {
    PixelSample px;
    Hit hit;
    SurfacePoint sp;
    vec4 k(0.f);
    if (!closest_opaque(ray, &hit, &sp, &k)) {
      px.color = background(ray);
      return px;
    }
    px.depth = hit.t;
    px.normal = sp.normal;
    px.albedo = vec3(k);
    px.color = shade(ray, sp, vec3(k));
    return px;
  }

  vec3 shade(const Ray& ray, const SurfacePoint& sp, vec3 k) const {
    const Material& m = p.materials[sp.material];
    vec3 d = glm::normalize(ray.direction);
    vec3 c = s.background.ambient * k + m.emission;
    for (const Light& l : s.lights) c += phong_light(m, k, sp.normal, d, sample_light(l, sp.position));
    return c;
  }
};

}  // namespace

RenderResult render(const PreparedScene& p, const RenderOptions& o) {
  const Scene& s = *p.scene;
  if (o.width <= 0 || o.height <= 0)
    throw Error("render: image size must be positive, got " + std::to_string(o.width) + "x" + std::to_string(o.height));
  if (o.camera < 0 || o.camera >= int(s.cameras.size()))
    throw Error("render: the scene has no camera " + std::to_string(o.camera) + " (it has " +
                std::to_string(s.cameras.size()) + ")");
  if (o.shadows || o.bounces > 0)
    throw Error("render: shadows and reflections (-shadows, -bounces) are not implemented yet");
  const int W = o.width, H = o.height;
  RenderResult res;
  res.width = W;
  res.height = H;
  res.color = Image(W, H, 3);
  if (o.depth) res.depth.assign(size_t(W) * H, infinity);
  if (o.normals) res.normals.assign(size_t(W) * H, vec3(0.f));
  if (o.albedo) res.albedo = Image(W, H, 3);

  const CameraFrame frame = make_camera_frame(s.cameras[o.camera], W, H);
  const Tracer tracer{p, o, s};
  const int ts = std::max(1, o.tile_size);
  const int tiles_x = (W + ts - 1) / ts, tiles_y = (H + ts - 1) / ts, tiles = tiles_x * tiles_y;
  std::atomic<int> done{0};
  std::mutex progress_mutex;

  auto render_tile = [&](int tile) {
    int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
    int x1 = std::min(W, x0 + ts), y1 = std::min(H, y0 + ts);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        // Row y counts from the top; the camera's j counts from the bottom.
        Ray ray = camera_ray(frame, float(x), float(H - 1 - y));
        PixelSample px = tracer.trace_camera(ray);
        size_t i = size_t(y) * W + x;
        float* c = res.color.at(x, y);
        c[0] = px.color.r; c[1] = px.color.g; c[2] = px.color.b;
        if (o.depth) res.depth[i] = px.depth;
        if (o.normals) res.normals[i] = px.normal;
        if (o.albedo) {
          float* a = res.albedo.at(x, y);
          a[0] = px.albedo.r; a[1] = px.albedo.g; a[2] = px.albedo.b;
        }
      }
    if (o.progress) {
      int n = ++done;
      std::lock_guard lock(progress_mutex);
      o.progress(float(n) / float(tiles));
    }
  };

  std::unique_ptr<tbb::global_control> limit;
  if (o.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
  if (o.threads == 1) {
    for (int t = 0; t < tiles; ++t) render_tile(t);
  } else {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t < r.end(); ++t) render_tile(t);
    });
  }
  return res;
}

std::string render_path_name(const PreparedScene&, const RenderOptions&) { return "generic"; }

}  // namespace rayform
