// The Python module's parts (python/): one header for what they share. The
// module is a thin layer over the pipeline (pipeline/): it fills a RenderJob
// as the command line does and renders it in memory.
#pragma once

#include "rayform/importers/scene_io.h"
#include "rayform/render/mesh_accel_cache.h"

#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <string>

namespace rayform::python {

namespace py = pybind11;

// A scene read from a file (rayform.Scene): read once, never changed, shared
// by every render of it; it outlives its file.
struct SceneObject {
  std::shared_ptr<const LoadedScene> loaded;
  std::string path;  // as given to load(); its extension names the format
  LoadOptions load;  // what it was read with (limits also bound prepare)
};

// A scene whose meshes' BVHs are kept from one render to the next
// (rayform.Prepared): a turntable or many cameras build them once. One render
// at a time (the cache moves into the render and back); others wait.
struct PreparedObject {
  SceneObject scene;
  std::shared_ptr<MeshAccelCache> cache = std::make_shared<MeshAccelCache>();
  std::shared_ptr<std::mutex> busy = std::make_shared<std::mutex>();
};

// A path given as str or os.PathLike, for `what` (TypeError otherwise).
std::string path_argument(const py::handle& value, const char* what);

// load(path, **options): throws rayform::Error, ValueError for bad options.
// With `decode_textures`, the texture files it names are decoded into it (it
// then renders when they are gone); convert() copies them as they are.
SceneObject load_scene_object(const std::string& path, const py::kwargs& options, bool decode_textures = true);

void add_scene(py::module_& m);
void add_render(py::module_& m);
void add_files(py::module_& m);

}  // namespace rayform::python
