// The render job's FrameSpread (pipeline/frame_spread.h) over the ranks of
// an MPI job: the load's and prepare's exchanges among the ranks
// (rank_work_share.h), the agreement that every rank reads the same file and
// has its scene ready, the tiles over the ranks (distributed_frame.h), and
// rank 0 as the writer.
#pragma once

#include "rayform/pipeline/frame_spread.h"

#include <memory>
#include <string>

namespace rayform::distributed {

// Collective from the first exchange on: every rank makes one for the same
// job, with the same `input` (the scene file, whose size the ranks compare).
// With `stats`, every rank's share of the work is printed by rank 0 after
// the render (after_render).
std::unique_ptr<FrameSpread> spread_frame_over_ranks(const std::string& input, bool stats);

}  // namespace rayform::distributed
