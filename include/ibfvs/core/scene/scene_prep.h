#pragma once
// Scene preparation: everything a run needs before a GL context exists, read
// once. The mesh (read or generated, subdivided, ordered for the GPU), netCDF
// scalars, normals and curvature when something needs them, displacement, the
// field (and the steps of an unsteady one), the colour and beta scalars with
// their ranges, the camera, dt from the step in pixels, the surface image.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/core/scene/scene.h"

namespace ibfvs {

/// The data at one time step of an unsteady scene, on the prepared mesh.
struct StepData {
  std::vector<glm::vec3> field;  ///< per vertex of the step's surface
  /// Where the surface moved (the first step's triangles, other points: a
  /// moving or deforming mesh): positions and normals per vertex, in the
  /// prepared mesh's order; empty: the prepared mesh's own.
  std::vector<glm::vec3> positions, normals;
  /// Where the step's triangles differ from the first step's (a topology
  /// change, refinement, another vertex count): its own prepared mesh, with
  /// `field` and the scalars on its vertices; null: the prepared mesh's.
  std::shared_ptr<const TriMesh> mesh;
  std::vector<float> color_scalar, beta_scalar;  ///< per vertex, where coloured (else empty)
};

struct PreparedScene {
  Scene scene;  ///< as given
  int width = 512, height = 512;
  int frames = 150;                 ///< resolved (frames 0: the automatic lock's frame + 60)
  int lock_at = Scene::kLockNever;  ///< resolved (kLockAuto becomes a frame)
  RenderSettings settings;
  std::shared_ptr<const TriMesh> mesh;
  std::string mesh_name;         ///< what messages call it: the file name, spec or demo
  bool demo = false;             ///< no mesh given: the built-in demo
  FieldSpec field_spec;          ///< the field in force (with the elements)
  std::vector<glm::vec3> field;  ///< per vertex, at the first time step
  std::size_t step_count = 1;    ///< > 1: an unsteady field with this many steps
  /// The data at a step (0 <= k < step_count; step 0 is `field` and `mesh`
  /// with the scalars). Throws SettingError naming the file and the step.
  std::function<StepData(std::size_t)> step_data;
  /// The time of each step (step_count of them, from the time key's first)
  /// as the data states it: a netCDF field's dates from its CF time axis
  /// (time_labels). Empty where the data states none.
  std::vector<std::string> step_labels;
  /// The mesh as given, before subdivision and GPU order: its vertex count,
  /// topology_hash, and the new index of each of its vertices (empty:
  /// unchanged). A later state of it (prepare_change) with the same
  /// triangles maps onto the prepared mesh with them.
  std::size_t source_vertices = 0;
  std::uint64_t source_topology = 0;
  std::vector<unsigned> vertex_order;
  std::vector<float> color_scalar, beta_scalar;
  CameraParams camera;
  std::optional<CameraParams> lock_camera;
  float dt = 0.0f;      ///< world units per frame
  float max_px = 0.0f;  ///< pixels per frame of the fastest vertex
  /// The fastest vertex's pixels per unit of dt in the scene's camera at its
  /// size, over the steps played (0: nothing moves): a new step fits dt from
  /// it without reading the steps again (scene_dt).
  float pixel_speed = 0.0f;
  ImageU8 surface_image;              ///< read once; empty: none
  std::vector<std::string> warnings;  ///< repaired input, slow settings: for the front end to show
};

/// The one way a scene becomes renderer settings: its texture settings
/// (alpha, beta, noise profile, rate and spike width, inject, colours,
/// colour map, advect view, noise space, fixed colour and beta ranges), its
/// image-space step (image_normalize: every point moves `step` pixels), its
/// noise scale and seed, over `base` (what a preparation found: the size,
/// percentile ranges, the object-noise cell). Throws SettingError naming the
/// key of a value that is not valid.
[[nodiscard]] RenderSettings scene_settings(const Scene& scene, RenderSettings base);

/// dt by the one rule: the scene's dt key where it gives one, else the time
/// step that moves the fastest vertex, `pixel_speed` pixels per unit of dt,
/// the scene's step in pixels (dt_for_step; 0 where nothing moves).
/// Normalised in image space (image_normalize) every point moves `step`
/// pixels whatever dt is: it then only has to be > 0, which this gives
/// where anything moves.
[[nodiscard]] float scene_dt(const Scene& scene, float pixel_speed);
/// The same for a host that knows its fastest vector in world units and
/// the world units a pixel spans at its focal point.
[[nodiscard]] float scene_dt(const Scene& scene, float world_speed, double world_per_pixel);

/// The field as messages name it (FieldSpec::to_string), with the time of
/// the step it shows, or of the first and last steps it plays, where the
/// data states them (step_labels): "wind:FILE:UWND:VWND at time index 6
/// (1982-07-18 11:00)", "... at time index 0 to 11 (... to ...)".
[[nodiscard]] std::string field_text(const PreparedScene& prepared);

/// Checks the scene and prepares it. Throws InputError naming the file, or
/// SettingError naming the key whose value is wrong.
PreparedScene prepare_scene(const Scene& scene);

/// The same for a mesh the caller already has (arrays from Python, a host
/// application's data), standing in for the scene's mesh key: checked,
/// normals computed when it has none, subdivided and ordered like a file's.
/// `name` is what messages call it.
PreparedScene prepare_scene(const Scene& scene, TriMesh mesh, const std::string& name);

/// The next state of the prepared scene's mesh, given as the caller has it
/// (a host's next time step, moved points, changed arrays: `mesh` in the
/// order and with the meaning of the mesh the scene was prepared from). With
/// the same triangles (topology_hash) it takes the prepared mesh's order and
/// triangles, its points and arrays its own (normals from `mesh` where it has
/// them, else computed); otherwise it is prepared afresh. The field and the
/// colour and beta scalars follow the scene (their ranges stay the prepared
/// scene's); camera, dt and settings stay. Throws InputError naming `name`.
PreparedScene prepare_change(const PreparedScene& prepared, TriMesh mesh, const std::string& name);

/// A host's time steps as one unsteady scene (ParaView's data over its
/// times): `states` in time order, each the surface as the host has it (the
/// meaning prepare_scene's mesh has). The first is prepared as
/// prepare_scene(scene, mesh, name) prepares it; each later one is a step on
/// it as prepare_change takes it: its points where they moved, a mesh of its
/// own where its triangles differ, its vectors and scalars. Colour and beta
/// ranges are the first state's; dt and the fastest vertex count every step
/// played. One state: prepare_scene's scene. Throws InputError naming
/// `name` and the step.
PreparedScene prepare_states(const Scene& scene, std::vector<TriMesh> states,
                             const std::string& name);

/// The prepared scene for another image size: the same mesh (shared, not read
/// again), field and scalars, with dt from the step in pixels (unless the
/// scene gives dt) and the object-noise cell for that size. Throws
/// SettingError for a size outside 1..16384.
PreparedScene resized(const PreparedScene& prepared, int width, int height);
/// The same in place (nothing copied): the size, the fastest vertex's
/// speed in the scene's camera (every step played is read again), dt and
/// the object-noise cell.
void fit_to_size(PreparedScene& prepared, int width, int height);

/// The fastest vertex's speed again for a new field (every step played is
/// read again), and dt from it: what a caller that replaced `field` owes
/// the prepared scene.
void fit_field(PreparedScene& prepared);

/// Takes `next`, the prepared scene's scene with some keys changed, the
/// way a running animation does: the one change plan (plan_change: each
/// changed key's effect, one table for every front end) applied to the
/// prepared scene where the animation can take it. Texture settings and the
/// noise grid go into its settings (scene_settings); a new tangent mode
/// evaluates the field again; the camera keys move its camera; a new size
/// and a new camera fit it again (fit_to_size); a new step or field fits dt
/// (scene_dt). `world_per_pixel`: world units a pixel spans at the mesh
/// centre as the frames are drawn, for an object-space noise cell turned on.
/// Returns the plan; with plan.prepare (a key needs the scene prepared
/// again: the mesh, the field, a scalar, a percentile range) it changes
/// nothing. Everything is checked before anything changes: throws
/// SettingError for settings that are not valid.
ChangePlan apply_change(PreparedScene& prepared, const Scene& next, float world_per_pixel);

/// The surface a step shows: its own mesh where it has one, else the
/// prepared mesh, with the step's points where it moved (what the
/// topology of a step is found on: the Session's overlay, `ibfvs
/// topology`, the page).
TriMesh step_surface(const PreparedScene& prepared, const StepData& step);

/// The prepared scene with `style`'s look, as the viewer's style keys give it
/// (the style's defaults over the scene), when that look takes the same data:
/// what changes is texture settings (key_effect: Live), the noise scale
/// and seed and the step (dt follows). Empty when the style needs other data:
/// curvature colours, a field of its own (the particles and principal styles
/// are pictures of the principal directions), random cells, its own camera.
/// Throws SettingError for settings the style makes invalid.
std::optional<PreparedScene> restyled(const PreparedScene& prepared, Style style);

/// The mesh's thinnest bounding-box axis (+X, +Y or +Z): the height axis of a
/// terrain.
glm::vec3 thinnest_axis(const TriMesh& mesh);

}  // namespace ibfvs
