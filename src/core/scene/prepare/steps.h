#pragma once
// Inside prepare_scene (scene_prep.cpp): its one context, the Preparation,
// and its eight steps in the order it runs them, in four files of this
// folder: load.cpp: settings (scene_settings), load (the mesh), series (a
// series' steps); camera.cpp: orient (the height axis and the camera's
// keys), pace (dt, the warnings about it, the automatic lock frame);
// scalars.cpp: surface_scalars (netCDF scalars, curvature, displacement),
// colours (the colour and beta scalars and their ranges, the surface
// image); field.cpp: field (the field, and the data of each step). Also
// (steps_on_mesh.cpp) what they share with prepare_change, resized and
// apply_change: a step's data on the prepared mesh, and the fit to an
// image (its size, the fastest vertex's speed, dt).

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs::prep {

// What the steps of one preparation share: the scene, what they have made
// of it so far, and what a later step reads of an earlier one's work.
struct Preparation {
  Preparation(const Scene& scene, std::optional<LoadedMesh> host_mesh)
      : s(scene), given(std::move(host_mesh)) {}
  const Scene& s;
  std::optional<LoadedMesh> given;  // a host's mesh; else load reads s.mesh
  PreparedScene p;                  // the result
  LoadedMesh loaded;                // what load read (its series, its vertex order)
  std::shared_ptr<TriMesh> mesh;    // the prepared mesh
  std::string label;                // the mesh as messages name it
  std::optional<FieldSpec> field_spec, default_field;
  std::size_t time_first = 0;  // the time key's first step (0 without one)
  bool series = false;         // the mesh is a series of steps
  std::size_t series_first = 0, series_last = 0;
  // The points as read: a later state whose points equal these stands still.
  std::shared_ptr<const std::vector<glm::vec3>> still;
  glm::vec3 up{0.0f, 1.0f, 0.0f};  // the height axis
};

// The steps, in order (scene_prep.cpp: prepare).
void settings(Preparation& c);
void load(Preparation& c);
void series(Preparation& c);
void orient(Preparation& c);
void surface_scalars(Preparation& c);
void field(Preparation& c);
void pace(Preparation& c);
void colours(Preparation& c);

// Runs `f`, turning a plain InputError into a SettingError of `key`.
template <class F>
auto for_key(const char* key, F&& f) {
  try {
    return f();
  } catch (const SettingError&) {
    throw;
  } catch (const InputError& e) {
    throw SettingError(key, e.what());
  }
}

// What a step's surface is put on the prepared mesh with.
struct StepContext {
  std::shared_ptr<const TriMesh> mesh;  // the prepared mesh (the first step's)
  // Its points as read, in its order, before any displacement: a step whose
  // points equal these stands still.
  std::shared_ptr<const std::vector<glm::vec3>> still;
  std::vector<unsigned> order;  // new index of each vertex as given
  std::size_t source_vertices = 0;
  std::uint64_t source_topology = 0;
  FieldSpec spec;
  TangentMode tangent = TangentMode::Project;
  bool reverse = false;
  std::string color_by, beta_by;
};

// Throws InputError naming `where` and the point where a point is not finite.
void check_finite(const std::vector<glm::vec3>& points, const std::string& where);
// A step's arrays (in file vertex order) onto the mesh, reordered like it.
void take_arrays(TriMesh& mesh, const TriMesh& step, const std::vector<unsigned>& order);
// A surface of the prepared mesh's points with triangles of its own (as
// many points, points_correspond), on those points in the prepared order;
// none where it is not.
std::optional<TriMesh> on_prepared_points(const StepContext& c, const TriMesh& given,
                                          const std::string& where, bool arrays_only = false);
// A step's surface as given on the prepared mesh (steps_on_mesh.cpp): the
// prepared triangles with its points (same), or triangles of its own on
// the prepared mesh's points in their order where the points correspond
// (points_correspond), else a mesh of its own.
TriMesh mesh_on(const StepContext& c, TriMesh given, const std::string& where, bool arrays_only,
                bool& same, bool& moved, bool same_known = false);
// The field and scalars of a surface, as the scene evaluates them.
void evaluate_step(const StepContext& c, const TriMesh& on, StepData& d);
StepData step_on_mesh(const StepContext& c, TriMesh given, const std::string& where,
                      bool arrays_only = false);
// The steps, each read once while they fit in a share of the memory.
std::function<StepData(std::size_t)> cached_steps(std::function<StepData(std::size_t)> read,
                                                  std::size_t count);
// The steps a run plays.
std::size_t steps_played(const PreparedScene& p);
// The positions a step's surface has.
const std::vector<glm::vec3>& step_positions(const StepData& d, const TriMesh& mesh);
bool wants_curvature(const std::string& name);
// A field with a time axis of its own (wind:, sample:): the time key steps
// through it, not through the mesh's series.
bool own_time(const FieldSpec& spec);
// Checks that need no file.
void check(const Scene& s);
// The image size and what follows from it with the scene's camera; returns
// the fastest vertex's pixels per unit of dt (0: nothing moves).
float fit_to_image(PreparedScene& p, int width, int height);
// The fastest vertex's speed at the size and camera as they are (every step
// played read again: p.pixel_speed), and dt from it (fit_dt).
void fit_speed(PreparedScene& p);
// dt and max_px from p.pixel_speed by the one rule (scene_dt): no step read.
void fit_dt(PreparedScene& p);

}  // namespace ibfvs::prep
