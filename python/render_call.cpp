// rayform.render, rayform.prepare and Prepared.render: the arguments filled
// into a RenderJob as the command line fills it (pipeline/render_job.h), the
// scene made ready and prepared as run_render_job does, and the render kept
// in memory: arrays of the values the command line writes to an EXR (color)
// and a PNG (color8), and the per-pixel outputs. The GIL is released while
// the job runs; Ctrl-C stops it between tiles.
#include "module_parts.h"
#include "rayform/base/error.h"
#include "rayform/base/thread_limit.h"
#include "rayform/image/image_file.h"
#include "rayform/pipeline/job_arguments.h"
#include "rayform/pipeline/render_job.h"
#include "rayform/render/aov_images.h"
#include "rayform/render/color_output.h"
#include "rayform/render/prepared_scene.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <thread>

namespace rayform::python {
namespace {

std::string type_name(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
}

// A sequence of `n` numbers (or n_max with n_min <= count), for `what`.
std::vector<float> numbers(const py::handle& value, const char* what, size_t n_min, size_t n_max) {
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value))
    throw py::type_error(std::string(what) + ": expected a sequence of numbers, got " + type_name(value));
  std::vector<float> v;
  for (const py::handle& x : py::reinterpret_borrow<py::sequence>(value)) {
    if (!py::isinstance<py::int_>(x) && !py::isinstance<py::float_>(x))
      throw py::type_error(std::string(what) + ": expected numbers, got " + type_name(x));
    v.push_back(x.cast<float>());
  }
  if (v.size() < n_min || v.size() > n_max)
    throw py::value_error(std::string(what) + ": expected " + std::to_string(n_min) +
                          (n_max != n_min ? " to " + std::to_string(n_max) : "") + " numbers, got " +
                          std::to_string(v.size()));
  for (float x : v)
    if (!std::isfinite(x)) throw py::value_error(std::string(what) + ": expected finite numbers");
  return v;
}

int integer(const py::handle& value, const char* what) {
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
    throw py::type_error(std::string(what) + ": expected an int, got " + type_name(value));
  return value.cast<int>();
}

float number(const py::handle& value, const char* what) {
  if (!py::isinstance<py::int_>(value) && !py::isinstance<py::float_>(value))
    throw py::type_error(std::string(what) + ": expected a number, got " + type_name(value));
  return value.cast<float>();
}

bool flag(const py::handle& value, const char* what) {
  if (!py::isinstance<py::bool_>(value))
    throw py::type_error(std::string(what) + ": expected True or False, got " + type_name(value));
  return value.cast<bool>();
}

std::string text(const py::handle& value, const char* what) {
  if (!py::isinstance<py::str>(value))
    throw py::type_error(std::string(what) + ": expected a str, got " + type_name(value));
  return value.cast<std::string>();
}

// What a call asks for besides the job: which arrays.
struct Wanted {
  bool color = true, color8 = false, depth = false, normal = false, albedo = false;
  bool float_pass() const { return color || depth || normal || albedo; }
};

// background=: (r, g, b) display values 0..1, or "#RRGGBB" (job_arguments.h).
vec3 background_argument(const py::handle& value) {
  if (py::isinstance<py::str>(value)) {
    const std::string s = value.cast<std::string>();
    const std::optional<vec3> c = background_from_hex(s);
    if (!c) throw py::value_error("background: expected (r, g, b) with each 0..1 or '#RRGGBB', got '" + s + "'");
    return *c;
  }
  const std::vector<float> v = numbers(value, "background", 3, 3);
  const vec3 c(v[0], v[1], v[2]);
  if (std::string expected = background_problem(c); !expected.empty())
    throw py::value_error("background: expected " + expected);
  return c;
}

// A name among `names` (job_arguments.h), for `what`.
std::string choice(const py::handle& value, const char* what, const std::vector<std::string>& names) {
  const std::string s = text(value, what);
  if (std::find(names.begin(), names.end(), s) == names.end())
    throw py::value_error(std::string(what) + ": expected " + quoted_names(names) + ", got '" + s + "'");
  return s;
}

// The job of a render call: the same fields the command line's flags fill
// (cli/render_command.cpp), checked by the same functions (job_arguments.h,
// render_options_problem) and worded under the argument names.
RenderJob job_from_arguments(const py::kwargs& args, Wanted& wanted) {
  RenderJob job;
  std::optional<float> env_intensity, env_rotate;
  std::optional<std::string> env;
  bool camera_given = false;
  for (const auto& [key, value] : args) {
    const std::string name = py::str(key).cast<std::string>();
    const char* n = name.c_str();
    if (value.is_none()) continue;  // None: the default
    if (name == "size") {
      const std::vector<float> v = numbers(value, n, 2, 2);
      job.render.width = int(v[0]);
      job.render.height = int(v[1]);
      if (float(job.render.width) != v[0] || float(job.render.height) != v[1])
        throw py::value_error("size: expected whole numbers (width, height)");
      job.default_size = false;
    } else if (name == "camera") {
      job.render.camera = integer(value, n);
      camera_given = true;
    } else if (name == "orbit") {
      const std::vector<float> v = numbers(value, n, 2, 3);
      Orbit o{v[0], v[1], v.size() == 3 ? std::optional<float>(v[2]) : std::nullopt};
      if (std::string problem = orbit_problem(o); !problem.empty()) throw py::value_error("orbit: " + problem);
      job.orbit = o;
    } else if (name == "frame") {
      job.frame = flag(value, n);
    } else if (name == "look_from" || name == "look_at" || name == "up") {
      const std::vector<float> v = numbers(value, n, 3, 3);
      const vec3 p(v[0], v[1], v[2]);
      (name == "look_from" ? job.camera_adjust.look_from
       : name == "look_at" ? job.camera_adjust.look_at
                           : job.camera_adjust.up) = p;
    } else if (name == "fov") {
      const float f = number(value, n);
      if (std::string expected = fov_problem(f); !expected.empty()) throw py::value_error("fov: expected " + expected);
      job.camera_adjust.fov_deg = f;
    } else if (name == "spp") {
      job.render.spp = integer(value, n);
    } else if (name == "target_error") {
      job.render.target_error = number(value, n);
    } else if (name == "max_spp") {
      job.render.max_spp = integer(value, n);
    } else if (name == "shadows") {
      job.render.shadows = flag(value, n);
    } else if (name == "bounces") {
      job.render.bounces = integer(value, n);
      job.default_bounces = false;
    } else if (name == "threads") {
      job.render.threads = integer(value, n);
    } else if (name == "background") {
      job.background = background_argument(value);
    } else if (name == "transparent") {
      job.transparent = flag(value, n);
    } else if (name == "exposure") {
      job.render.exposure_ev = number(value, n);
    } else if (name == "tonemap") {
      job.render.tone_map = *tone_map_from_name(choice(value, n, tone_map_names()));
      job.default_tone_map = false;
    } else if (name == "encoding") {
      job.color = *encoding_from_name(choice(value, n, encoding_names()));
    } else if (name == "filter") {
      job.render.filter = *filter_from_name(choice(value, n, filter_names()));
    } else if (name == "sampler") {
      job.render.sampler = *sampler_from_name(choice(value, n, sampler_names()));
    } else if (name == "env") {
      env = py::isinstance<py::str>(value) ? value.cast<std::string>() : path_argument(value, n);
    } else if (name == "env_intensity") {
      env_intensity = number(value, n);
      if (std::string expected = env_intensity_problem(*env_intensity); !expected.empty())
        throw py::value_error("env_intensity: expected " + expected);
    } else if (name == "env_rotate") {
      env_rotate = number(value, n);
      if (std::string expected = env_rotation_problem(*env_rotate); !expected.empty())
        throw py::value_error("env_rotate: expected " + expected);
    } else if (name == "aovs") {
      if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value))
        throw py::type_error("aovs: expected a sequence of 'depth', 'normal', 'albedo', got " + type_name(value));
      for (const py::handle& a : py::reinterpret_borrow<py::sequence>(value)) {
        const std::string s = text(a, n);
        if (s == "depth") wanted.depth = true;
        else if (s == "normal" || s == "normals") wanted.normal = true;
        else if (s == "albedo") wanted.albedo = true;
        else throw py::value_error("aovs: expected 'depth', 'normal' or 'albedo', got '" + s + "'");
      }
    } else if (name == "color") {
      wanted.color = flag(value, n);
    } else if (name == "color8") {
      wanted.color8 = flag(value, n);
    } else {
      throw py::type_error("render() got an unexpected keyword argument '" + name + "'");
    }
  }
  // The keywords are the job's field names (job_arguments.h).
  if (std::string conflict = camera_conflict(job, camera_given, [](const std::string& field) { return field; });
      !conflict.empty())
    throw py::value_error(conflict);
  job.environment = environment_from_arguments(env, env_intensity, env_rotate);
  // The one check of the render parameters (render.h), under the argument names.
  if (std::string problem = render_options_problem(job.render); !problem.empty()) throw py::value_error(problem);
  if (!wanted.float_pass() && !wanted.color8) throw py::value_error("color, color8 and aovs: nothing asked for");
  return job;
}

// Raised in the render's thread when the caller's thread saw a signal.
struct Stopped {};

// One render of `prepared` with `options`, tile by tile until `stop`.
RenderResult render_until(const PreparedScene& prepared, const RenderOptions& options, const std::atomic<bool>& stop) {
  RenderResult result = allocate_render_result(prepared, options);
  const int count = tile_grid(options).count();
  std::atomic<int> next{0};
  render_tiles_from(
      prepared, options,
      [&]() -> int {
        if (stop.load(std::memory_order_relaxed)) return -1;
        const int t = next.fetch_add(1, std::memory_order_relaxed);
        return t < count ? t : -1;
      },
      result);
  if (stop.load()) throw Stopped{};
  return result;
}

// The file names that decide each pass's options as they decide the command
// line's: an EXR (linear floats, premultiplied alpha) and a PNG (8-bit,
// straight alpha). Nothing is written.
constexpr const char* float_file = "color.exr";
constexpr const char* bytes_file = "color.png";

struct Passes {
  ReadyScene ready;
  std::optional<RenderResult> floats, bytes;
  ColorOutput color_output;
};

Passes run_job(RenderJob job, const Wanted& wanted, PreparedObject* keep, const std::atomic<bool>& stop) {
  Passes out;
  const std::shared_ptr<void> thread_limit = limit_threads(job.render.threads);
  out.ready = load_job_ready(job);
  PrepareOptions po;
  po.limits = job.load.limits;
  po.cache = keep ? keep->cache.get() : nullptr;
  PreparedScene prepared = prepare_scene(out.ready.scene, po);
  out.color_output = ColorOutput{out.ready.color.scene, job.color};
  if (wanted.float_pass()) {
    RenderJob j = job;
    j.output = float_file;
    if (wanted.depth) j.depth = DepthOutput{0.f, 1.f, "depth.exr"};
    if (wanted.normal) j.normals = "normals.exr";
    if (wanted.albedo) j.albedo = "albedo.exr";
    out.floats = render_until(prepared, job_render_options(j, out.ready), stop);
  }
  if (wanted.color8) {
    RenderJob j = job;
    j.output = bytes_file;
    out.bytes = render_until(prepared, job_render_options(j, out.ready), stop);
  }
  if (keep) keep_mesh_accels(prepared, po.bvh, *keep->cache);
  return out;
}

// Runs `work` on a thread of its own while this one, the GIL released but for
// a moment every 20 ms, checks for signals (Ctrl-C): on one it sets `stop`,
// which the render sees before its next tile, and raises it.
template <class Work>
auto interruptible(Work work, std::atomic<bool>& stop) {
  std::packaged_task<decltype(work())()> task(std::move(work));
  auto done = task.get_future();
  bool signalled = false;
  {
    py::gil_scoped_release unlocked;
    std::thread worker(std::move(task));
    while (done.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) {
      py::gil_scoped_acquire locked;
      if (PyErr_CheckSignals() != 0) {
        signalled = true;
        stop = true;
        break;
      }
    }
    worker.join();
  }
  if (signalled) throw py::error_already_set();
  return done.get();
}

// A buffer handed to NumPy without a copy: the array owns `data` through a capsule.
template <class Container, class T>
py::array owned_array(Container&& data, std::vector<py::ssize_t> shape) {
  auto* held = new Container(std::move(data));
  py::capsule owner(held, [](void* p) { delete static_cast<Container*>(p); });
  return py::array_t<T>(shape, reinterpret_cast<const T*>(held->data()), owner);
}

py::dict arrays(Passes& p, const Wanted& wanted) {
  py::dict out;
  if (p.floats) {
    RenderResult& r = *p.floats;
    const py::ssize_t h = r.height, w = r.width;
    if (wanted.color) {
      // As the EXR holds it: linear (sRGB only when forced), alpha premultiplied.
      Image image = r.coverage.empty() ? std::move(r.color) : color_with_alpha(r);
      if (writes_srgb(p.color_output, image_file(float_file))) encode_srgb_in_place(image);
      const py::ssize_t c = image.channels;
      out["color"] = owned_array<std::vector<float>, float>(std::move(image.pixels), {h, w, c});
    }
    if (wanted.depth) out["depth"] = owned_array<std::vector<float>, float>(std::move(r.depth), {h, w});
    if (wanted.normal) {
      static_assert(sizeof(vec3) == 3 * sizeof(float));
      out["normal"] = owned_array<std::vector<vec3>, float>(std::move(r.normals), {h, w, 3});
    }
    if (wanted.albedo) out["albedo"] = owned_array<std::vector<float>, float>(std::move(r.albedo.pixels), {h, w, 3});
  }
  if (p.bytes) {
    // As the PNG holds it: 8-bit, straight alpha.
    RenderResult& r = *p.bytes;
    Image8 image = r.coverage.empty() ? std::move(r.color8) : color8_with_alpha(r);
    const py::ssize_t c = image.channels;
    out["color8"] = owned_array<std::vector<unsigned char>, uint8_t>(std::move(image.pixels),
                                                                     {py::ssize_t(r.height), py::ssize_t(r.width), c});
  }
  return out;
}

py::dict render_scene(const SceneObject& scene, const py::kwargs& args, PreparedObject* keep) {
  Wanted wanted;
  RenderJob job = job_from_arguments(args, wanted);
  job.input = scene.path;
  job.load = scene.load;
  job.preloaded = scene.loaded;
  std::atomic<bool> stop{false};
  Passes passes = interruptible(
      [&] {
        std::unique_lock<std::mutex> one_at_a_time;
        if (keep) one_at_a_time = std::unique_lock<std::mutex>(*keep->busy);
        return run_job(job, wanted, keep, stop);
      },
      stop);
  return arrays(passes, wanted);
}

// render()'s first argument: a Scene, a Prepared or a path (read with no options).
py::dict render_any(const py::object& what, const py::kwargs& args) {
  if (py::isinstance<PreparedObject>(what)) {
    PreparedObject& p = what.cast<PreparedObject&>();
    return render_scene(p.scene, args, &p);
  }
  if (py::isinstance<SceneObject>(what)) return render_scene(what.cast<const SceneObject&>(), args, nullptr);
  const std::string path = path_argument(what, "scene");
  return render_scene(load_scene_object(path, py::kwargs(), false), args, nullptr);  // read once, as the program
}

const char* render_doc = R"(render(scene, *, size=None, camera=None, orbit=None, frame=False, look_from=None,
       look_at=None, up=None, fov=None, spp=None, target_error=None, max_spp=None,
       shadows=False, bounces=None, background=None, transparent=False, exposure=0.0,
       tonemap=None, encoding='auto', env=None, env_intensity=None, env_rotate=None,
       filter='box', sampler='stratified', aovs=(), color=True, color8=False,
       threads=0) -> dict[str, numpy.ndarray]

Renders a scene with the command line's defaults (`rayform render`): every
argument is its flag of the same name, and None (or leaving it out) takes the
same default.

scene: a Scene (rayform.load), a Prepared (rayform.prepare) or a path.
size: (width, height) in pixels (default 512x512 for OBJ and glTF, 200x200 for course scenes).
camera: index of the file's camera (default 0).
orbit: (azimuth, elevation[, distance]) in degrees (and world units): a camera
  looking at the bounds' centre, replacing the file's cameras (--orbit).
frame: replace the file's cameras with the default one framing the bounds.
look_from, look_at, up: (x, y, z) world positions / direction moving the camera.
fov: the camera's opening angle, degrees, 0 < fov < 180.
spp: samples per pixel (default 1: the pixel centre).
target_error: adaptive sampling's standard error per pixel (replaces spp); max_spp its most samples (256).
shadows: shadow rays to every light.
bounces: reflection/refraction depth (default: the scene's, as the command line).
background: (r, g, b) display values 0..1 or '#RRGGBB'.
transparent: alpha as a fourth channel: color premultiplied (as the EXR), color8 straight (as the PNG).
exposure: stops (colour scaled by 2**exposure).
tonemap: 'khr-neutral', 'aces' or 'none' for color8 (default: the scene's).
encoding: 'auto', 'raw' or 'srgb' (--color).
env: environment file, 'studio' or 'none'; env_intensity, env_rotate (degrees).
filter: 'box' or 'tent'; sampler: 'stratified' or 'random' (spp > 1).
aovs: any of 'depth', 'normal', 'albedo'.
color: return 'color'; color8: return 'color8'.
threads: worker threads (0: all).

Returns a dict of arrays, rows from the top:
  'color':  float32 (h, w, 3) or (h, w, 4) with transparent: linear values, as the
            command line writes them to an .exr.
  'color8': uint8 (h, w, 3 or 4), sRGB-encoded (raw for course scenes): as the .png.
  'depth':  float32 (h, w): hit distance along the centre ray, inf where it misses.
  'normal': float32 (h, w, 3): unit world-space shading normal, 0 where it misses.
  'albedo': float32 (h, w, 3): the unlit surface colour, linear.
color8 is a render of its own (the 8-bit values come from the render loop).

The GIL is released while it renders: threads may render at once. Ctrl-C stops
it between tiles (KeyboardInterrupt). Raises rayform.Error for a bad file or
a failed render, ValueError or TypeError naming a bad argument.)";

}  // namespace

void add_render(py::module_& m) {
  static const std::string prepared_render_doc =
      std::string("Prepared.") + render_doc + "\n\n(Prepared.render takes no scene: it renders its own.)";
  py::class_<PreparedObject>(m, "Prepared",
                             "A scene prepared by rayform.prepare: its meshes' BVHs are kept from one render to the "
                             "next (turntables, many cameras). Renders one at a time.")
      .def_property_readonly(
          "scene", [](const PreparedObject& p) { return p.scene; }, "The Scene it renders.")
      .def(
          "render", [](PreparedObject& p, const py::kwargs& args) { return render_scene(p.scene, args, &p); },
          prepared_render_doc.c_str())
      .def("__repr__", [](const PreparedObject& p) { return "<rayform.Prepared '" + p.scene.path + "'>"; });
  m.def("render", &render_any, py::arg("scene"), render_doc);
  m.def(
      "prepare",
      [](const py::object& what, const py::kwargs& options) {
        PreparedObject p;
        if (py::isinstance<SceneObject>(what)) {
          if (!options.empty()) throw py::type_error("prepare: load options apply to a path, not a Scene");
          p.scene = what.cast<const SceneObject&>();
        } else {
          p.scene = load_scene_object(path_argument(what, "scene"), options);
        }
        p.cache->source = &p.scene.loaded->scene;
        return p;
      },
      py::arg("scene"),
      R"(prepare(scene, **load_options) -> Prepared

A scene (a Scene, or a path read with load()'s options) that renders many
views without building its meshes' BVHs again: prepared.render(orbit=(az, el))
for a turntable. The first render builds them.)");
}

}  // namespace rayform::python
