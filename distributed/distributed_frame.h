// One frame rendered by every rank of an MPI job (ranks.h): tiles handed out
// dynamically by a WorkCounter (a rank that finishes early takes more), and
// gathered by rank 0 (tile_gather.h). Each pixel is rendered as render()
// renders it, so rank 0's image is bit for bit the one-process image,
// whatever the number of ranks and however the tiles fall.
#pragma once

#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"

namespace rayform::distributed {

// What one rank did, for --stats.
struct FrameShare {
  long long tiles = 0;        // tiles this rank rendered
  double render_s = 0.0;      // seconds rendering them (until the counter ran out)
  double render_cpu_s = 0.0;  // CPU seconds of this process (all its threads) meanwhile: its work, whatever else runs
  double gather_s = 0.0;      // seconds sending them to rank 0 (receiving, on rank 0)
};

// Collective. At rank 0 the whole image; elsewhere a result holding that
// rank's tiles only. options.progress, when set, is called with the fraction
// of all tiles handed out so far (set it on rank 0 only). An error on any
// rank ends the whole job (abort_ranks): the others would wait for its tiles.
RenderResult render_frame_over_ranks(const PreparedScene& scene, const RenderOptions& options, FrameShare* share);

}  // namespace rayform::distributed
