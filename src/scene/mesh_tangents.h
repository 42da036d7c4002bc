// Tangents for normal textures (placeholder declaration; its part of issue 30 fills it).
#pragma once

#include "rayform/scene/scene.h"

#include <vector>

namespace rayform {

std::vector<vec4> corner_tangents(const Mesh& mesh, int uv_set);

}  // namespace rayform
