// Memory of the acceleration structure, in bytes per triangle: our MeshAccel
// (memory_bytes(): BVH nodes, vertices in leaf order, triangle ids; it needs
// nothing else at traversal time) against what Embree allocates for the same
// triangles, through its device memory monitor (rtcSetDeviceMemoryMonitorFunction).
// Embree shares the mesh's vertex and index buffers, which the renderer keeps
// anyway for shading, so both figures are the memory added on top of the mesh.
//
// Counters (bytes/triangle): ours, embree (held after rtcCommitScene, MEDIUM),
// embree_high (HIGH), embree_build_peak (peak while building, MEDIUM);
// ratio = ours / embree.
#include "bench_main.h"
#include "bench_meshes.h"

using namespace rayform;
using namespace rayform::bench;

namespace {

struct EmbreeBytes {
  double held = 0., peak = 0.;
};

EmbreeBytes embree_bytes(const BenchMesh& m, RTCBuildQuality q) {
  EmbreeMemory& mem = embree_device().memory;
  int64_t before = mem.current.load();
  mem.reset_peak();
  EmbreeScene e(m, q);
  return {double(mem.current.load() - before), double(mem.peak.load() - before)};
}

void bm_memory(benchmark::State& state, std::string mesh) {
  const BenchMesh* m = mesh_or_skip(state, mesh);
  if (!m) return;
  double ours = 0.;
  EmbreeBytes med, high;
  for (auto _ : state) {
    {
      MeshAccel a = build_mesh_accel(m->vertex_span(), m->indices);
      ours = double(a.memory_bytes());
    }
    med = embree_bytes(*m, RTC_BUILD_QUALITY_MEDIUM);
    high = embree_bytes(*m, RTC_BUILD_QUALITY_HIGH);
  }
  double n = double(m->triangle_count());
  state.counters["ours"] = ours / n;
  state.counters["embree"] = med.held / n;
  state.counters["embree_high"] = high.held / n;
  state.counters["embree_build_peak"] = med.peak / n;
  state.counters["ratio"] = ours / med.held;
  state.counters["ours_MB"] = ours / 1048576.;
  state.counters["embree_MB"] = med.held / 1048576.;
  state.counters["triangles"] = n;
  state.SetLabel("B/tri");
}

}  // namespace

int main(int argc, char** argv) {
  for_each_mesh([](const std::string& mesh) {
    benchmark::RegisterBenchmark(("memory/" + mesh).c_str(), bm_memory, mesh)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  });
  return run_benchmarks(argc, argv);
}
