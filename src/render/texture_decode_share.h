// The textures and cube-map faces a prepared scene uses, decoded from their
// files (decode_texture), optionally shared among cooperating processes
// (WorkShare: the ranks of a frame spread over MPI ranks). Shared, part p
// decodes the items j with j % parts == p (with its own threads), and one
// exchange gives every part every item, so that each ends with the images
// one process decodes, byte for byte.
#pragma once

#include "rayform/base/work_share.h"
#include "rayform/image/image.h"
#include "rayform/render/texture_sampler.h"
#include "rayform/scene/scene.h"

#include <utility>
#include <vector>

namespace rayform {

// One image to decode: a Scene texture handle and where its image goes.
using TextureDecodeItem = std::pair<int, TextureImage*>;

// Decodes every item's texture of `scene` into its destination. Throws
// rayform::Error as decode_texture does (shared: on every part, the first
// failed item's error in `items` order). With a shared `share` and at least
// two items every part must pass the same items: the call is collective (one
// exchange); otherwise it makes none.
void decode_textures(const Scene& scene, const std::vector<TextureDecodeItem>& items, const DecodeOptions& options,
                     const WorkShare* share = nullptr);

}  // namespace rayform
