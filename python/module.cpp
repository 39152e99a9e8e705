// The Python module ibfvs._ibfvs (pybind11): an animation on the library's
// Session in its own headless EGL context. The package ibfvs (python/ibfvs)
// wraps it: inputs as people have them, render(), Jupyter display.
//
// Errors become Python exceptions (InputError and SettingError: ValueError;
// GraphicsError: RuntimeError); the GIL is released while frames render.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/trigonometric.hpp>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/polygon.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/page/web_page.h"
#include "ibfvs/render/export.h"
#include "ibfvs/render/host_flow.h"
#include "ibfvs/render/session.h"
#include "ibfvs/video/video_writer.h"
#include "topology_binding.h"
#ifdef IBFVS_HAVE_VTK
#include "ibfvs/vtk/vtk_io.h"
#endif

namespace py = pybind11;

namespace ibfvs::python {
namespace {

using Options = std::vector<std::pair<std::string, std::string>>;

Scene scene_from(const std::string& scene_file, const Options& options) {
  Scene scene = scene_file.empty() ? Scene{} : read_scene(scene_file);
  std::vector<Setting> settings;
  for (const auto& [key, text] : options) settings.push_back({key, text, ""});
  apply_settings(scene, settings);
  return scene;
}

// A numpy view of an image the capsule keeps alive, rows top first (the
// image is stored bottom-up: a negative row stride, no copy).
template <class Image, class T>
py::array top_first(Image image, bool drop_alpha) {
  auto* owned = new Image(std::move(image));
  py::capsule keep(owned, [](void* p) { delete static_cast<Image*>(p); });
  const auto w = static_cast<py::ssize_t>(owned->width);
  const auto h = static_cast<py::ssize_t>(owned->height);
  const auto c = static_cast<py::ssize_t>(owned->channels);
  const auto item = static_cast<py::ssize_t>(sizeof(T));
  T* last_row = owned->pixels.data() + (h - 1) * w * c;
  return py::array_t<T>({h, w, drop_alpha ? std::min<py::ssize_t>(c, 3) : c},
                        {-w * c * item, c * item, item}, last_row, keep);
}

class Animation {
  // The context current on the calling thread for one call, one call at a
  // time (Python threads may call while another renders without the GIL).
  class Current {
   public:
    explicit Current(const Animation& a) : lock_(a.mutex_), context_(a.context_) {
      context_.make_current();
    }
    ~Current() { context_.release_current(); }
    Current(const Current&) = delete;
    Current& operator=(const Current&) = delete;

   private:
    std::lock_guard<std::mutex> lock_;
    gl::HeadlessContext& context_;
  };

 public:
  // A mesh from arrays (mesh set) or the scene's own mesh key.
  Animation(Scene desc, std::optional<TriMesh> mesh, std::string name)
      : desc_(std::move(desc)),
        mesh_(mesh ? std::make_shared<const TriMesh>(std::move(*mesh)) : nullptr),
        name_(std::move(name)) {
    const Current current(*this);
    session_ = mesh_ ? std::make_unique<Session>(prepare_scene(desc_, *mesh_, name_), mesh_, name_)
                     : std::make_unique<Session>(prepare_scene(desc_));
  }
  ~Animation() {
    const Current current(*this);  // the GL objects go with their context current
    session_.reset();
  }
  Animation(const Animation&) = delete;
  Animation& operator=(const Animation&) = delete;

  void step(int frames) {
    if (frames < 0) throw SettingError("frames", "must not be negative");
    // In chunks, with Ctrl-C (KeyboardInterrupt) checked between them.
    constexpr int kChunk = 16;
    for (int done = 0; done < frames;) {
      const int n = std::min(kChunk, frames - done);
      {
        py::gil_scoped_release release;
        const Current current(*this);
        for (int k = 0; k < n; ++k) session_->advance();
      }
      done += n;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }

  py::array image(bool alpha) {
    const Current current(*this);
    return top_first<ImageU8, std::uint8_t>(session_->read_output(), !alpha);
  }

  py::array texture() {
    const Current current(*this);
    return top_first<ImageF, float>(session_->read_texture(), false);
  }

  // Any keys, by the session's rules (Session::set, key_effect): texture
  // settings, the step, the noise grid, the tangent mode, the camera and the
  // size change on the running animation; anything else prepares the scene
  // again, in the session (the texture goes on over the same points).
  void set(const Options& options) {
    Scene desc = desc_;
    std::vector<Setting> settings;
    for (const auto& [key, text] : options) settings.push_back({key, text, ""});
    apply_settings(desc, settings);
    const Current current(*this);
    static_cast<void>(session_->set(desc));
    desc_ = desc;
  }

  // The next state of the data (a time step of the caller's own loop):
  // the texture goes on (Session::change_data), the points' motion carried
  // into it; `frames` frames of the new state are rendered now (0: the next
  // step shows it).
  void update(TriMesh mesh, int frames) {
    if (frames < 0) throw SettingError("frames", "must not be negative");
    py::gil_scoped_release release;
    const Current current(*this);
    mesh_ = std::make_shared<const TriMesh>(std::move(mesh));
    session_->change_surface(mesh_, name_.empty() ? "the data" : name_);
    for (int k = 0; k < frames; ++k) session_->render(session_->camera());
  }

  // The texture from noise again, the data and settings as they are.
  void restart() {
    const Current current(*this);
    session_->restart();
  }

  void lock() {
    const Current current(*this);
    session_->lock();
  }
  void unlock() {
    const Current current(*this);
    session_->unlock();
  }
  [[nodiscard]] bool locked() const { return session_->locked(); }

  // Renders `frames` more frames into a video file (any of the command's
  // containers); returns the path.
  std::string write_video(const std::string& path, int frames, double fps) {
    if (frames < 1) throw SettingError("frames", "a video needs at least one frame");
    if (!is_video_path(path))
      throw InputError(path + ": not a video file name (.mp4 .mkv .webm .mov .avi .gif)");
    py::gil_scoped_release release;
    const Current current(*this);
    const PreparedScene& p = session_->scene();
    VideoWriter video(path, p.width, p.height, fps);
    for (int k = 0; k < frames; ++k) {
      session_->advance();
      ImageU8 frame = video.spare();
      session_->read_output(frame);
      video.write(std::move(frame));
    }
    video.close();
    return path;
  }

  // The surface with the current texture (section 3.7; lock first to keep
  // the texture where it is): .obj, .gltf, .glb or .vtp, the PNG beside it.
  std::vector<std::string> export_model(const std::string& path) {
    const Current current(*this);
    const ExportReport report =
        export_textured_model(session_->renderer(), *session_->scene().mesh, path);
    std::vector<std::string> files;
    for (const auto& f : report.files) files.push_back(f.string());
    return files;
  }

  // The scene as a self-contained web page (docs/web.md): the browser
  // animates it from the first frame, with the settings in force now.
  [[nodiscard]] py::bytes page() const { return web_page(session_->scene()); }
  // The page's scene as (header JSON, block bytes): the notebook widget's.
  [[nodiscard]] std::pair<std::string, py::bytes> page_parts() const {
    WebPageParts parts = web_page_parts(session_->scene());
    return {std::move(parts.header),
            py::bytes(reinterpret_cast<const char*>(parts.block.data()), parts.block.size())};
  }

  void save_png(const std::string& path) {
    const Current current(*this);
    write_png(session_->read_output(), path);
  }

  [[nodiscard]] int frame() const { return session_->frame(); }
  [[nodiscard]] std::pair<int, int> size() const {
    return {session_->scene().width, session_->scene().height};
  }
  [[nodiscard]] std::size_t step_count() const { return session_->scene().step_count; }
  [[nodiscard]] std::vector<std::string> step_labels() const {
    return session_->scene().step_labels;
  }
  [[nodiscard]] std::string renderer_name() const {
    const Current current(*this);
    return context_.renderer();
  }
  [[nodiscard]] std::vector<std::string> warnings() const { return session_->scene().warnings; }
  [[nodiscard]] std::string scene_toml_text() const { return scene_toml(desc_); }

 private:
  mutable std::mutex mutex_;
  mutable gl::HeadlessContext context_;
  Scene desc_;
  std::shared_ptr<const TriMesh> mesh_;  // the caller's arrays (null: the scene's mesh key)
  std::string name_;
  std::unique_ptr<Session> session_;
};

// ---------------------------------------------------------------- arrays in

template <class T>
using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;

std::size_t rows_of(const py::array& a, py::ssize_t columns, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != columns) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
      shape += (d ? ", " : "") + std::to_string(a.shape(d));
    throw py::value_error(std::string(what) + " must have shape (n, " + std::to_string(columns) +
                          "), got " + shape + (a.ndim() == 1 ? ",)" : ")"));
  }
  return static_cast<std::size_t>(a.shape(0));
}

std::vector<glm::vec3> vec3s(const Array<double>& a, const char* what) {
  const std::size_t n = rows_of(a, 3, what);
  std::vector<glm::vec3> out(n);
  const double* d = a.data();
  for (std::size_t i = 0; i < n; ++i)
    out[i] = glm::vec3(static_cast<float>(d[3 * i]), static_cast<float>(d[3 * i + 1]),
                       static_cast<float>(d[3 * i + 2]));
  return out;
}

// A TriMesh from arrays: points (n, 3), triangles (m, 3) of indices, named
// per-vertex and per-triangle arrays (1 or 3 components).
TriMesh mesh_from_arrays(const Array<double>& points, const Array<std::int64_t>& triangles,
                         const std::map<std::string, py::array>& point_arrays,
                         const std::map<std::string, py::array>& cell_arrays) {
  TriMesh mesh;
  mesh.positions = vec3s(points, "points");
  const std::size_t n = mesh.positions.size();
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw py::value_error("points: point " + std::to_string(i) +
                            " has a non-finite coordinate (NaN or infinity)");
  }
  const std::size_t m = rows_of(triangles, 3, "triangles");
  const std::int64_t* t = triangles.data();
  mesh.triangles.resize(m);
  for (std::size_t f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t id = t[3 * f + static_cast<std::size_t>(k)];
      if (id < 0 || static_cast<std::size_t>(id) >= n)
        throw py::value_error("triangles: triangle " + std::to_string(f) + " refers to point " +
                              std::to_string(id) + " but there are " + std::to_string(n) +
                              " points");
      mesh.triangles[f][static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(id);
    }
  if (m == 0) throw py::value_error("triangles: there are none");
  const auto add = [&](const std::string& name, const py::array& raw, bool per_triangle) {
    const std::size_t expected = per_triangle ? m : n;
    const Array<double> a = Array<double>::ensure(raw);
    if (!a) throw py::type_error("array '" + name + "' is not numeric");
    const std::size_t rows = a.ndim() >= 1 ? static_cast<std::size_t>(a.shape(0)) : 0;
    if (rows != expected)
      throw py::value_error("array '" + name + "' has " + std::to_string(rows) +
                            " rows, expected " + std::to_string(expected) +
                            (per_triangle ? " (one per triangle)" : " (one per point)"));
    if (a.ndim() == 1 || (a.ndim() == 2 && a.shape(1) == 1)) {
      std::vector<float> v(rows);
      for (std::size_t i = 0; i < rows; ++i) v[i] = static_cast<float>(a.data()[i]);
      mesh.scalars[name] = per_triangle ? triangle_to_vertex(mesh, v) : v;
    } else if (a.ndim() == 2 && a.shape(1) == 3) {
      std::vector<glm::vec3> v = vec3s(a, name.c_str());
      mesh.vector_arrays[name] = per_triangle ? triangle_to_vertex(mesh, v) : v;
    } else {
      throw py::value_error("array '" + name + "' must have 1 or 3 components per row");
    }
  };
  for (const auto& [name, a] : point_arrays) add(name, a, false);
  for (const auto& [name, a] : cell_arrays)
    if (!mesh.scalars.count(name) && !mesh.vector_arrays.count(name)) add(name, a, true);
  return mesh;
}

// A 4x4 matrix as VTK hands it (row-major numpy) in glm's columns.
glm::mat4 mat4_of(const Array<double>& a, const char* what) {
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw py::value_error(std::string(what) + " must be a 4x4 matrix");
  glm::mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = static_cast<float>(a.data()[4 * r + c]);
  return m;
}

// A flat array of int64 values. Its shape goes in as a vector, and numpy
// works out the strides: Debian's pybind11 (2.10) reads the item size off
// numpy 2's descriptor wrongly, and array_t(count, ...) strides by 0 there
// (every element the first one).
py::array_t<std::int64_t> int64_array(std::span<const std::int64_t> values) {
  py::array_t<std::int64_t> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(values.size())});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// A polygon list's triangles (core/mesh/polygon.h): the split every reader
// makes, the same cells given the same triangles again by `memory`.
// offsets (c + 1,) and ids as VTK's cell arrays hold them; returns the
// triangles (m, 3) and each one's polygon (m,).
py::tuple split_polygons(const Array<std::int64_t>& offsets, const Array<std::int64_t>& ids,
                         const Array<double>& points, SplitMemory* memory) {
  if (offsets.ndim() != 1 || ids.ndim() != 1)
    throw py::value_error("polygons: offsets and ids must be flat arrays");
  const std::vector<glm::vec3> at = vec3s(points, "points");
  const PolygonList<std::int64_t> list{
      std::span<const std::int64_t>(offsets.data(), static_cast<std::size_t>(offsets.shape(0))),
      std::span<const std::int64_t>(ids.data(), static_cast<std::size_t>(ids.shape(0)))};
  if (list.offsets.empty()) throw py::value_error("polygons: offsets must start with 0");
  std::int64_t last = 0;
  for (std::size_t c = 0; c < list.offsets.size(); ++c) {
    const std::int64_t o = list.offsets[c];
    if ((c == 0 && o != 0) || o < last ||
        static_cast<std::uint64_t>(o) > static_cast<std::uint64_t>(list.ids.size()))
      throw py::value_error("polygons: offset " + std::to_string(c) + " is " + std::to_string(o) +
                            " (offsets start at 0, never decrease and end at the " +
                            std::to_string(list.ids.size()) + " ids)");
    last = o;
  }
  if (static_cast<std::uint64_t>(last) != static_cast<std::uint64_t>(list.ids.size()))
    throw py::value_error("polygons: the offsets end at " + std::to_string(last) + ", not at the " +
                          std::to_string(list.ids.size()) + " ids");
  for (std::size_t k = 0; k < list.ids.size(); ++k)
    if (list.ids[k] < 0 || static_cast<std::uint64_t>(list.ids[k]) >= at.size())
      throw py::value_error("polygons: id " + std::to_string(k) + " is point " +
                            std::to_string(list.ids[k]) + " but there are " +
                            std::to_string(at.size()) + " points");
  const std::shared_ptr<const PolygonSplit> split =
      memory ? memory->split(list, at)
             : std::make_shared<const PolygonSplit>(ibfvs::split_polygons(list, at));
  const auto m = static_cast<py::ssize_t>(split->triangles.size());
  py::array_t<std::int64_t> triangles(std::vector<py::ssize_t>{m, 3});
  std::int64_t* t = triangles.mutable_data();
  for (std::size_t k = 0; k < split->triangles.size(); ++k)
    for (std::size_t j = 0; j < 3; ++j) t[3 * k + j] = split->triangles[k][j];
  const std::vector<std::int64_t> polygon(split->polygon.begin(), split->polygon.end());
  return py::make_tuple(triangles, int64_array(polygon));
}

// A VTK-style legacy cell list [n, i0, .., n, ...] (PyVista's `faces`) as
// offsets and ids (VTK's own layout).
py::tuple cells_of_faces(const Array<std::int64_t>& faces) {
  if (faces.ndim() != 1)
    throw py::type_error("faces must be a flat integer array [n, i0, i1, ..., n, ...]");
  const std::int64_t* f = faces.data();
  const auto size = static_cast<std::size_t>(faces.shape(0));
  std::vector<std::int64_t> offsets{0}, ids;
  ids.reserve(size);
  for (std::size_t i = 0, cell = 0; i < size; ++cell) {
    const std::int64_t n = f[i];
    if (n < 0 || static_cast<std::uint64_t>(n) > size - i - 1)
      throw py::value_error("faces: cell " + std::to_string(cell) + " says " + std::to_string(n) +
                            " points but the array ends before");
    ids.insert(ids.end(), f + i + 1, f + i + 1 + n);
    offsets.push_back(static_cast<std::int64_t>(ids.size()));
    i += 1 + static_cast<std::size_t>(n);
  }
  return py::make_tuple(int64_array(offsets), int64_array(ids));
}

// The flow texture in a host's own picture (ibfvs/pyvista.py: a VTK render
// window's context, current in its render callback): HostFlow.
class HostLayer {
 public:
  void set(const Options& options) {
    Scene s = host_.scene();
    std::vector<Setting> settings;
    for (const auto& [key, text] : options) settings.push_back({key, text, ""});
    apply_settings(s, settings);
    host_.set_scene(s);
  }
  void set_frames_per_step(int frames) { host_.set_frames_per_step(frames); }

  // points (n, 3), triangles (m, 3), vectors (n, 3); colour positions (n,)
  // in the host's table where it colours by an array.
  void set_surface(const Array<double>& points, const Array<std::int64_t>& triangles,
                   const Array<double>& vectors, const std::optional<Array<double>>& colour,
                   const std::string& name) {
    std::map<std::string, py::array> arrays;
    if (colour) arrays[kHostColour] = *colour;
    TriMesh mesh = mesh_from_arrays(points, triangles, arrays, {});
    mesh.vectors = vec3s(vectors, "vectors");
    if (mesh.vectors.size() != mesh.positions.size())
      throw py::value_error("vectors: " + std::to_string(mesh.vectors.size()) + " rows for " +
                            std::to_string(mesh.positions.size()) + " points");
    host_.set_surface(std::move(mesh), name);
  }

  void set_colours(const Array<double>& table, std::array<double, 3> nan) {
    HostColours c;
    if (table.size() > 0) c.table = vec3s(table, "table");
    c.nan = glm::vec3(nan[0], nan[1], nan[2]);
    host_.set_colours(std::move(c));
  }

  void render(std::array<int, 4> viewport, const Array<double>& view,
              const Array<double>& projection, double focal_distance,
              std::array<double, 3> surface_color) {
    HostRender r;
    r.origin = glm::ivec2(viewport[0], viewport[1]);
    r.width = viewport[2];
    r.height = viewport[3];
    r.view = ViewState{mat4_of(view, "view"), mat4_of(projection, "projection")};
    r.focal_distance = focal_distance;
    r.surface_color = glm::vec3(surface_color[0], surface_color[1], surface_color[2]);
    host_.render(r);
  }

  void release() { host_.release(); }
  [[nodiscard]] int frame() const { return host_.frame(); }

 private:
  HostFlow host_;
};

// A Python callable that C++ may hold and copy on any thread: the object is
// released with the GIL held, and the std::function copies share it without
// touching its reference count.
std::shared_ptr<py::object> held(py::object fn) {
  return {new py::object(std::move(fn)), [](py::object* o) {
            // After Python's end (a static's destructor at exit) there is no
            // GIL to take: the object went with the interpreter.
            if (!Py_IsInitialized()) return;
            py::gil_scoped_acquire gil;
            delete o;
          }};
}

// A result of Python's netCDF reader: `call` (under the GIL) gives a tuple
// of `fields` values, `take` makes them the library's; Python's errors and
// a result of another shape are one InputError naming the file.
template <class Call, class Take>
auto reader_result(const std::filesystem::path& path, const std::string& what, std::size_t fields,
                   Call call, Take take) {
  py::gil_scoped_acquire gil;
  try {
    const py::tuple r = call();
    if (r.size() != fields)
      throw InputError(path.string() + ": the netCDF reader returned no " + what);
    return take(r);
  } catch (const py::error_already_set& e) {
    throw InputError(one_line(path.string() + ": " + e.what()));
  } catch (const py::cast_error& e) {
    throw InputError(path.string() + ": the netCDF reader returned no " + what + " (" + e.what() +
                     ")");
  }
}

// The netCDF reader of builds without netCDF-C (the pip package): Python's
// functions (ibfvs/__init__.py, through xarray), their errors one InputError
// naming the file.
void set_netcdf_reader(py::object variables, py::object read, py::object time_axis) {
  if (variables.is_none() || read.is_none() || time_axis.is_none()) {
    set_lonlat_reader({});
    return;
  }
  LonLatReader reader;
  reader.variables = [fn = held(std::move(variables))](const std::filesystem::path& path) {
    py::gil_scoped_acquire gil;
    try {
      return (*fn)(path.string()).cast<std::vector<std::string>>();
    } catch (const py::error_already_set& e) {
      throw InputError(one_line(path.string() + ": " + e.what()));
    }
  };
  reader.read = [fn = held(std::move(read))](const std::filesystem::path& path,
                                             const std::string& variable, std::size_t t) {
    // (lon, lat, values (lat, lon), units, time steps)
    return reader_result(
        path, "grid", 5, [&] { return (*fn)(path.string(), variable, t); },
        [&](const py::tuple& r) {
          LonLatGrid g;
          g.name = variable;
          g.lon = r[0].cast<std::vector<double>>();
          g.lat = r[1].cast<std::vector<double>>();
          const auto values =
              r[2].cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
          g.values.assign(values.data(), values.data() + values.size());
          g.units = r[3].cast<std::string>();
          g.time_steps = r[4].cast<std::size_t>();
          return g;
        });
  };
  reader.time_axis = [fn = held(std::move(time_axis))](const std::filesystem::path& path,
                                                       const std::string& variable) {
    // (values, units, calendar)
    return reader_result(
        path, "time axis", 3, [&] { return (*fn)(path.string(), variable); },
        [](const py::tuple& r) {
          TimeAxis axis;
          axis.values = r[0].cast<std::vector<double>>();
          axis.units = r[1].cast<std::string>();
          axis.calendar = r[2].cast<std::string>();
          return axis;
        });
  };
  set_lonlat_reader(std::move(reader));
}

}  // namespace
}  // namespace ibfvs::python

PYBIND11_MODULE(_ibfvs, m) {
  using namespace ibfvs;
  using ibfvs::python::Animation;
  m.doc() = "ibfvs: image based flow visualization for curved surfaces (the C++ core)";
  gl::tune_process_for_rendering();  // as the command does: llvmpipe's threads and memory
#ifdef IBFVS_HAVE_VTK
  vtk::install_vtk_io();
  m.attr("has_vtk") = true;
#else
  m.attr("has_vtk") = false;
#endif
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SettingError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const GraphicsError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  m.def(
      "keys",
      [] {
        std::vector<std::tuple<std::string, std::string, std::vector<std::string>>> out;
        const Scene defaults;
        for (const SceneKey& k : scene_keys())
          out.emplace_back(std::string(k.name), k.help, k.get(defaults));
        return out;
      },
      "Every scene key: (name, help, default text forms).");

  m.attr("__version__") = IBFVS_VERSION;
  // What this build does itself; the pip package leaves both to Python's
  // own packages (imageio-ffmpeg's ffmpeg, xarray).
  m.attr("has_libav") = IBFVS_HAVE_LIBAV != 0;
  m.attr("has_netcdf") = netcdf_built_in();
  m.def("set_netcdf_reader", &ibfvs::python::set_netcdf_reader, py::arg("variables"),
        py::arg("read"), py::arg("time_axis"),
        "Where the build has no netCDF-C: VARIABLES(path) -> names, READ(path, variable,\n"
        "time_index) -> (lon, lat, values, units, time_steps) and TIME_AXIS(path, variable) ->\n"
        "(values, units, calendar) read netCDF files (None, None, None: none).");
  m.def(
      "topology",
      [](const std::string& scene_file, const ibfvs::python::Options& options, double scale,
         double min_strength, double min_length) {
        return ibfvs::python::topology_of(
            prepare_scene(ibfvs::python::scene_from(scene_file, options)),
            ibfvs::TopologyOptions{scale, min_strength, min_length});
      },
      py::arg("scene_file"), py::arg("options"), py::arg("scale"), py::arg("min_strength"),
      py::arg("min_length"), "The topology of a scene's field at each step (ibfvs.topology).");
  m.def(
      "topology",
      [](const ibfvs::python::Array<double>& points,
         const ibfvs::python::Array<std::int64_t>& triangles,
         const std::map<std::string, py::array>& point_arrays,
         const std::map<std::string, py::array>& cell_arrays, const ibfvs::python::Options& options,
         const std::string& name, double scale, double min_strength, double min_length) {
        return ibfvs::python::topology_of(
            prepare_scene(
                ibfvs::python::scene_from("", options),
                ibfvs::python::mesh_from_arrays(points, triangles, point_arrays, cell_arrays),
                name),
            ibfvs::TopologyOptions{scale, min_strength, min_length});
      },
      py::arg("points"), py::arg("triangles"), py::arg("point_arrays"), py::arg("cell_arrays"),
      py::arg("options"), py::arg("name"), py::arg("scale"), py::arg("min_strength"),
      py::arg("min_length"), "The topology of the field on a mesh of arrays (ibfvs.topology).");
  m.def(
      "topology_defaults",
      [] {
        const ibfvs::TopologyOptions o;
        return std::make_tuple(o.scale, o.min_strength, o.min_length);
      },
      "The topology's default options: (scale, min_strength, min_length).");
  m.def(
      "topology_kinds",
      [] {
        std::vector<std::tuple<int, std::string, std::array<int, 3>>> out;
        for (const ibfvs::KindStyle& k : ibfvs::kind_styles())
          out.emplace_back(k.kind, k.name, std::array<int, 3>{k.rgb[0], k.rgb[1], k.rgb[2]});
        return out;
      },
      "Every `kind` of the topology: (value, name, (r, g, b)).");
  m.def(
      "table_positions",
      [](const std::vector<float>& values, double lo, double hi, bool log) {
        return ibfvs::table_positions(values, lo, hi, log);
      },
      py::arg("values"), py::arg("lo"), py::arg("hi"), py::arg("log"),
      "Positions in a colour table of VALUES over [LO, HI] (log: base-10), as VTK maps them.");
  py::class_<SplitMemory>(m, "SplitMemory",
                          "How polygons split into triangles, kept for the next state of the same "
                          "cells (a moving mesh's steps: the same triangles at every step).")
      .def(py::init<>())
      .def_property_readonly("size", &SplitMemory::size);
  m.def("split_polygons", &ibfvs::python::split_polygons, py::arg("offsets"), py::arg("ids"),
        py::arg("points"), py::arg("memory") = nullptr,
        "Triangles (m, 3) of polygons as VTK's cell arrays hold them, and each one's polygon\n"
        "(m,): the split every ibfvs reader makes; MEMORY gives the same cells the same\n"
        "triangles again, wherever their points moved.");
  m.def("cells_of_faces", &ibfvs::python::cells_of_faces, py::arg("faces"),
        "A VTK-style cell list [n, i0, ..., n, ...] as (offsets, ids).");
  py::class_<ibfvs::python::HostLayer>(m, "HostLayer",
                                       "The flow texture drawn in a host's own OpenGL context "
                                       "(ibfvs.pyvista); every call that draws needs it current.")
      .def(py::init<>())
      .def("set", &ibfvs::python::HostLayer::set, py::arg("options"))
      .def("set_frames_per_step", &ibfvs::python::HostLayer::set_frames_per_step)
      .def("set_surface", &ibfvs::python::HostLayer::set_surface, py::arg("points"),
           py::arg("triangles"), py::arg("vectors"), py::arg("colour"), py::arg("name"))
      .def("set_colours", &ibfvs::python::HostLayer::set_colours, py::arg("table"), py::arg("nan"))
      .def("render", &ibfvs::python::HostLayer::render, py::arg("viewport"), py::arg("view"),
           py::arg("projection"), py::arg("focal_distance"), py::arg("surface_color"))
      .def("release", &ibfvs::python::HostLayer::release)
      .def_property_readonly("frame", &ibfvs::python::HostLayer::frame);
  py::class_<Animation>(m, "Animation")
      .def(py::init([](const std::string& scene_file, const ibfvs::python::Options& options) {
             return std::make_unique<Animation>(ibfvs::python::scene_from(scene_file, options),
                                                std::nullopt, "");
           }),
           py::arg("scene_file"), py::arg("options"))
      .def(py::init([](const ibfvs::python::Array<double>& points,
                       const ibfvs::python::Array<std::int64_t>& triangles,
                       const std::map<std::string, py::array>& point_arrays,
                       const std::map<std::string, py::array>& cell_arrays,
                       const ibfvs::python::Options& options, const std::string& name) {
             TriMesh mesh =
                 ibfvs::python::mesh_from_arrays(points, triangles, point_arrays, cell_arrays);
             return std::make_unique<Animation>(ibfvs::python::scene_from("", options),
                                                std::move(mesh), name);
           }),
           py::arg("points"), py::arg("triangles"), py::arg("point_arrays"), py::arg("cell_arrays"),
           py::arg("options"), py::arg("name"))
      .def("step", &Animation::step, py::arg("frames") = 1, "Render FRAMES more frames.")
      .def("image", &Animation::image, py::arg("alpha") = true,
           "The shown image, uint8 (H, W, 4) or (H, W, 3), rows top first (a view, no copy).")
      .def("texture", &Animation::texture,
           "The texture F_t, float32 (H, W, 4), rows top first (a view, no copy).")
      .def("_set", &Animation::set, py::arg("options"))
      .def(
          "_update",
          [](Animation& a, const ibfvs::python::Array<double>& points,
             const ibfvs::python::Array<std::int64_t>& triangles,
             const std::map<std::string, py::array>& point_arrays,
             const std::map<std::string, py::array>& cell_arrays, int frames) {
            a.update(ibfvs::python::mesh_from_arrays(points, triangles, point_arrays, cell_arrays),
                     frames);
          },
          py::arg("points"), py::arg("triangles"), py::arg("point_arrays"), py::arg("cell_arrays"),
          py::arg("frames"))
      .def("restart", &Animation::restart,
           "Start the texture from noise again (a change of data or size never does).")
      .def("lock", &Animation::lock, "Lock the texture to the surface (section 3.7).")
      .def("unlock", &Animation::unlock)
      .def_property_readonly("locked", &Animation::locked)
      .def("write_video", &Animation::write_video, py::arg("path"), py::arg("frames"),
           py::arg("fps") = 30.0, "Render FRAMES more frames into a video file.")
      .def("export", &Animation::export_model, py::arg("path"),
           "The surface with the current texture as .obj, .gltf, .glb or .vtp (and the PNG);\n"
           "returns the files written.")
      .def("save_png", &Animation::save_png, py::arg("path"))
      .def("_page", &Animation::page, "The scene as a self-contained web page (bytes, UTF-8).")
      .def_static("_has_page", &ibfvs::has_web_runtime)
      .def("_page_parts", &Animation::page_parts,
           "The page's scene as (header JSON text, binary block bytes).")
      .def_static("_widget_module",
                  []() -> std::optional<std::string> {
                    const char* module = ibfvs::web_widget_module();
                    return module ? std::optional<std::string>(module) : std::nullopt;
                  })
      .def_static("_page_style", []() { return std::string(ibfvs::web_page_style()); })
      .def_property_readonly("frame", &Animation::frame)
      .def_property_readonly("size", &Animation::size)
      .def_property_readonly("step_count", &Animation::step_count)
      .def_property_readonly("step_labels", &Animation::step_labels,
                             "The time of each step as the data states it (a netCDF field's "
                             "dates), else [].")
      .def_property_readonly("renderer", &Animation::renderer_name)
      .def_property_readonly("warnings", &Animation::warnings)
      .def("scene_toml", &Animation::scene_toml_text, "The scene in force as a scene file (TOML).");
}
