// Baking transforms into shapes: a scene flattened to one group of shapes in
// world space (save_scene's --flatten), and the mesh and plane transforms it
// is made of (also used by the OBJ writer, which has no transforms).
#pragma once

#include "rayform/scene/scene.h"

#include <string>
#include <vector>

namespace rayform {

// The scene with every transform baked into the shapes: root group -> one shape
// node per instance, identity matrices, meshes copied per instance (normals by
// the inverse transpose, winding reversed under mirroring). Messages for spheres
// that had to be tessellated. `name` prefixes the messages.
Scene flatten_scene(const Scene& scene, int sphere_segments, const std::string& name,
                    std::vector<std::string>* messages);

// A mesh under an object-to-world matrix: positions transformed, normals by
// the inverse transpose (renormalised), winding reversed when m mirrors.
Mesh transform_mesh(const Mesh& mesh, const mat4& m);
// The plane n . p = d under m (unit normal in the result).
Plane transform_plane(const Plane& plane, const mat4& m);

}  // namespace rayform
