// Build time of the acceleration structure over the same triangles: ours
// (build_mesh_accel: bounds, BVH, vertices copied in leaf order) against
// Embree's rtcCommitScene (scene and geometry creation included; the mesh
// buffers are shared, not copied) at RTC_BUILD_QUALITY_MEDIUM (Embree's
// default: binned SAH), interleaved in each iteration; wall-clock time.
// build/MESH/threads:0/embree_high compares once with RTC_BUILD_QUALITY_HIGH
// (spatial splits; slow, so one iteration and one repetition).
// build/degenerate1M: 1M copies of one triangle (a hostile file, issue 12),
// next to build/torus1M: no SAH split exists, the builder splits by count.
//
// threads:0 = every hardware thread (both builders use TBB), threads:1 = one
// (a tbb::global_control caps both; not run for the 10M mesh).
// Counters: ours, embree in ms; ratio = ours / embree (time: < 1 means we
// build faster; the goal is <= 2).
#include "bench_main.h"
#include "bench_meshes.h"

#include <tbb/global_control.h>

using namespace rayform;
using namespace rayform::bench;

namespace {

void bm_build(benchmark::State& state, std::string mesh, int threads, RTCBuildQuality quality) {
  const BenchMesh* m = mesh_or_skip(state, mesh);
  if (!m) return;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  double ours_s = 0., embree_s = 0.;
  for (auto _ : state) {
    double t0 = wall_seconds(), t1;
    {
      MeshAccel a = build_mesh_accel(m->vertex_span(), m->indices);
      t1 = wall_seconds();  // freeing is not timed (nor for Embree)
      benchmark::DoNotOptimize(a);
    }
    {
      double s = wall_seconds();
      EmbreeScene e(*m, quality);
      embree_s += wall_seconds() - s;
    }
    ours_s += t1 - t0;
    state.SetIterationTime(t1 - t0);
  }
  double it = double(state.iterations());
  state.counters["ours"] = 1e3 * ours_s / it;
  state.counters["embree"] = 1e3 * embree_s / it;
  state.counters["ratio"] = ours_s / embree_s;
  state.counters["triangles"] = double(m->triangle_count());
  state.counters["Mtris_per_s"] = double(m->triangle_count()) * it / ours_s * 1e-6;
  state.SetLabel("ms");
}

}  // namespace

int main(int argc, char** argv) {
  auto register_mesh = [](const std::string& mesh) {
    for (int threads : {0, 1}) {
      if (threads == 1 && mesh == "torus10M") continue;
      register_manual_ms("build/" + mesh + "/threads:" + std::to_string(threads), bm_build, mesh, threads,
                         RTC_BUILD_QUALITY_MEDIUM);
    }
    register_manual_ms("build/" + mesh + "/threads:0/embree_high", bm_build, mesh, 0, RTC_BUILD_QUALITY_HIGH)
        ->Iterations(1)
        ->Repetitions(1);
  };
  for_each_mesh([&](const std::string& mesh) {
    register_mesh(mesh);
    // Degenerate input of the same size builds in about the same time.
    if (mesh == "torus1M") register_mesh("degenerate1M");
  });
  return run_benchmarks(argc, argv);
}
