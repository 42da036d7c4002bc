// The ranks of an MPI job as a WorkShare (rayform/base/work_share.h): part =
// rank, parts = ranks, the exchange an all-gather of byte strings over
// MPI_COMM_WORLD. Without MPI, or on one rank, a share of one part.
#pragma once

#include "rayform/base/work_share.h"

namespace rayform::distributed {

// Collective use only: every rank must make the same exchanges in the same order.
WorkShare rank_work_share();

}  // namespace rayform::distributed
