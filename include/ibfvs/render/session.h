#pragma once
// A session: one prepared scene on the GPU. It owns the renderer, the player
// of an unsteady scene (its field, and its surface where that moves or
// changes), the camera and the frame count, and steps the animation the way
// `ibfvs render` does (lock at the scene's frame, then the lock camera;
// orbit; the time steps). `ibfvs render`, `ibfvs view`, `ibfvs bench`,
// Python and ParaView all drive one. The texture outlives any change of data
// (change_data, a step of a series), of size (resize) or of the noise grid
// (rebuild): only a restart starts it from noise again.
//
// It is the one door to a running animation: every front end (the viewer,
// Python, both VTK mappers through HostFlow) changes it only here: keys by
// one rule (set: apply_change's plan, prepared again here where a key needs
// it), new data, one restart, a host's view (the camera it draws with or
// the world units a pixel spans: dt by the one rule, scene_dt), a host's
// colours and its compositing. Its images are read through it; the
// renderer itself is seen read-only, by the few that measure it.
//
// It needs a current OpenGL 4.5 context for its whole life and never makes
// one: ibfvs's own (gl::HeadlessContext, the viewer's window) or the host's
// (ParaView's render window). It leaves the host's framebuffer binding and
// viewport as it found them after each frame.

#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "ibfvs/core/fields/topology_morph.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/topology_overlay.h"

namespace ibfvs {

/// The scalar array of a host's surface that holds, per vertex, its
/// position in the host's colour table (table_positions): the prepared mesh
/// carries it in its own vertex order.
inline constexpr const char* kHostColour = "ibfvs:colour";

/// A host's colours: its table at evenly spaced positions 0..1 (empty: its
/// surface colour), the colour of values it cannot map (NaN), and its
/// surface's own colour.
struct HostColours {
  std::vector<glm::vec3> table;
  glm::vec3 nan{0.5f, 0.5f, 0.5f};
  glm::vec3 surface{1.0f};
  bool operator==(const HostColours&) const = default;
};

/// What Session::set did with a changed scene (apply_change's plan).
enum class SetResult {
  Applied,   ///< taken on the running animation
  NewView,   ///< taken, and the camera or the image size changed: a caller
             ///< with its own camera makes it again and tells fit_dt
  Prepared,  ///< a key needed the scene prepared again, and the session did:
             ///< new data, camera and time 0; the texture goes on where the
             ///< surface is the same (else it starts afresh)
};

/// When Session::set does the GPU's part of a change: now (the caller's
/// context current: the viewer, Python), or at the next frame (a host
/// such as ParaView or PyVista, whose context is current only in its
/// render). The change itself is checked, planned and taken now either way.
enum class Apply { Now, AtNextFrame };

/// Texture frames a host gives each change of its data (a time step) at
/// least, where its renders since the last change fell short (ParaView's
/// Frames Per Step): enough for the texture to take on the new flow, as
/// measured on two OpenFOAM results (docs/paraview.md, "Time").
inline constexpr int kDefaultFramesPerStep = 3;
inline constexpr int kMaxFramesPerStep = 200;

/// How many texture frames each render of a host gives (ParaView's mapper),
/// whatever its cadence: one; at a change of the data also the frames that
/// the renders of the last data fell short of frames_per_step, at the new
/// data. A step therefore gets at least frames_per_step frames: Save
/// Animation, which renders each step once, all of them at the step's own
/// data; Play and Sequence mode, which render a step several times, one a
/// render, with no jump at a change. Two renders of a step count as one:
/// Save Animation renders its first step twice (the time set, then the
/// picture taken). The data the texture started on counts as rendered once
/// too (a host renders it any number of times before it plays or saves:
/// those frames formed the texture, they owe the next step nothing), and a
/// restart gives frames_per_step, a new texture formed. A change that moves
/// a surface carrying its texture (a turning part) counts every render as
/// it is, the first data's too: the render that shows the step carries the
/// texture across it in its first frame, and each frame after that takes it
/// further from the picture before (the GUI's Play renders a step twice:
/// two frames at the change, not three; Play in pvbatch, many renders a
/// step: one, at the first change too).
class FramePacer {
 public:
  explicit FramePacer(int frames_per_step = kDefaultFramesPerStep) {
    set_frames_per_step(frames_per_step);
  }
  /// Clamped to 1..kMaxFramesPerStep.
  void set_frames_per_step(int frames);
  [[nodiscard]] int frames_per_step() const { return per_step_; }
  /// The frames of the next render. `changed`: its data differ from the
  /// last render's; `restart`: the texture starts afresh; `moved`: the
  /// change moved the surface's points (a moving mesh's step) under a
  /// texture they do not carry (carries_surface false: a field that holds
  /// the surface's motion), which gets all frames_per_step whatever the
  /// renders before: the texture left in the image takes them to form on
  /// the moved surface (one frame shows it half formed: docs/paraview.md,
  /// "Time"). A texture the surface carries needs none: it rides on it.
  /// `carried`: the change moved the points under a texture they carry.
  int next(bool changed, bool restart, bool moved = false, bool carried = false);

 private:
  int per_step_ = kDefaultFramesPerStep;
  int renders_ = 0;    // renders of the data as it is
  bool first_ = true;  // that data is the one the texture started on
};

/// Time t (in steps, from 0) of a series of `steps` steps as it plays: with
/// `loop` on from the last step back to the first (t modulo steps), else
/// held at the last step (the series ends there, as ParaView's does).
double session_time(double t, std::size_t steps, bool loop);

class Session {
 public:
  /// Uploads the mesh, field, scalars and surface image and initialises F_t
  /// (the scene's init). `source`, `name`: the mesh `scene` was prepared
  /// from where the caller gave one (a host's, Python's arrays), which a key
  /// that needs the scene prepared again prepares it from; null: the
  /// scene's own files. Throws GraphicsError without a current context.
  explicit Session(PreparedScene scene, std::shared_ptr<const TriMesh> source = nullptr,
                   std::string name = {});
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// The next frame of the scene's own run: at frame lock_at the texture
  /// locks and the camera becomes the lock camera; after frame 0 the camera
  /// orbits by the scene's orbit; an unsteady field advances by
  /// 1/frames_per_step step per frame.
  void advance();
  /// One frame seen by `camera` at the current time (the viewer's way:
  /// it moves the camera and the time itself).
  void render(const Camera& camera);
  /// The same with the host's own matrices (ParaView's camera and actor).
  void render(const ViewState& view);
  /// Moves an unsteady scene to time t, in steps (session_time: looping
  /// where the scene's loop key says so, else held at the last step);
  /// nothing for a steady one.
  void seek(double t);
  /// The time of the last seek as played (session_time).
  [[nodiscard]] double time() const { return time_; }

  /// Frames rendered so far.
  [[nodiscard]] int frame() const { return frame_; }
  /// The scene as prepared and changed: read-only (changes go through set,
  /// set_elements, change_surface, ...).
  [[nodiscard]] const PreparedScene& scene() const { return scene_; }
  /// The renderer, read-only, for what measures it (quality, export). A
  /// restart, a new size or noise grid or a scene prepared again makes a
  /// new one: a reference held across them is left dangling; the reads
  /// below ask the one in force.
  [[nodiscard]] const IbfvsRenderer& renderer() const { return *renderer_; }
  /// Texture frames the renderer in force has drawn (its contrast
  /// statistics' schedule).
  [[nodiscard]] int renderer_frame() const { return renderer_->frame(); }
  /// The settings on the renderer (the scene's, with a host's colours).
  [[nodiscard]] const RenderSettings& settings() const { return renderer_->settings(); }
  /// The camera advance() uses (the scene's, orbiting; the lock camera once locked).
  [[nodiscard]] Camera& camera() { return camera_; }
  /// World units per frame, by the one rule (dt_for_step): the scene's own
  /// dt key where it has one; else the fastest point moves the scene's step
  /// in pixels a frame, seen by the host's view where one was given
  /// (fit_dt, follow_host), else by the scene's camera. A new step, field,
  /// camera or size fits it again.
  [[nodiscard]] float dt() const { return dt_; }
  /// A host that draws with a camera of its own (the viewer, a snapshot):
  /// dt fits the step in its pixels, now and at each later change.
  void fit_dt(const Camera& camera);
  /// A host that knows the world units a pixel spans at its focal point and
  /// its fastest vector (VTK's mappers, through HostFlow): dt for them
  /// (dt_for_step); with image_normalize 1 where anything moves.
  void follow_host(double world_per_pixel, float speed);

  /// Takes `next`, the running scene with some keys changed, the way a
  /// running animation should (key_effect, one table for every front end):
  /// texture and display settings live; a new step rescales dt; a new noise
  /// scale rebuilds the grid and a new seed restarts it; a new tangent mode
  /// evaluates a steady field again; the camera keys move the view; a new
  /// size resamples the texture. The texture goes on through each of these.
  /// `seen_by`: the camera the frames are drawn with, where the caller has
  /// its own (the viewer): an object-space noise cell is sized for it.
  /// A key that needs the scene prepared again (the mesh, the field, a
  /// scalar, a percentile range, ...) prepares it here, from the scene's
  /// files or the source mesh (Prepared). Throws SettingError or
  /// InputError, changing nothing, for settings that are not valid or data
  /// that cannot be prepared. `when`: the GPU's part now, or at the next
  /// frame (Apply).
  SetResult set(const Scene& next, const Camera* seen_by = nullptr, Apply when = Apply::Now);
  /// Replaces the field (same vertex count), keeping the texture; dt fits it.
  void set_field(std::vector<glm::vec3> field);
  /// The flow elements of an element field (the viewer's editing): the
  /// field evaluated again with them, the texture going on. Throws
  /// InputError for an element that is not valid, changing nothing.
  void set_elements(std::vector<FlowElement> elements);
  /// Goes on with new data: a host's next time step, moved points, a changed
  /// array, another mesh; `next` is the scene prepared for it
  /// (prepare_change). The texture goes on from where it is: with the same
  /// triangles the surface moves from where the last frame drew it (its
  /// motion enters the advection, as the camera's does); with other
  /// triangles it is replaced and the texture stays where it is in the image
  /// until the flow takes it on. The next frame shows the new data; a host
  /// owes the texture a few frames at a change (kDefaultFramesPerStep).
  void change_data(PreparedScene next);
  /// The next state of the source mesh, as the caller has it (a host's time
  /// step, Python's update): prepare_change on the scene, then change_data;
  /// a key that needs preparing later prepares from it.
  void change_surface(std::shared_ptr<const TriMesh> mesh, const std::string& name);
  /// A new image size: the texture is resampled to it and goes on.
  void resize(int width, int height);
  /// The one restart (the viewer's button, Python's restart(), a host's
  /// restart or new seed): a new renderer with the settings in force, the
  /// texture from the scene's initial state (noise, or its random cells),
  /// frame 0, unlocked; the data, the time of a series, the camera, dt and
  /// a host's colours stay.
  void restart();

  // ---- a host's own controls (the viewer's mouse, section 3.7)
  /// Section 3.7: the texture stops and stays on the surface as seen now
  /// (IbfvsRenderer::lock); unlock goes on from it.
  void lock();
  void unlock();
  [[nodiscard]] bool locked() const { return renderer_->locked(); }
  /// The next frame's F_t and the noise move by `pixels` (a drag).
  void shift_image(glm::vec2 pixels);
  /// While the host drags its camera the texture advects in `view`, not the
  /// scene's advect key; nullopt: the scene's again.
  void override_advect_view(std::optional<AdvectView> view);

  // ---- a host's colours and its compositing (VTK's mappers)
  /// The host's colours over the scene's colour keys from now on: a table
  /// read at the surface's kHostColour positions, else its surface colour.
  void set_host_colours(const HostColours& colours);
  /// The probe step's world length (IbfvsRenderer::set_probe_length): the
  /// whole surface's of a host of several processes.
  void set_probe_length(float world);
  /// The contrast statistics wait for take_composited (several processes).
  void defer_statistics(bool on);
  /// A distributed render's composited F_t, and F where the statistics were
  /// due (then run): as read_texture_raw and read_output_raw give them.
  void take_composited(const ImageF& texture, const ImageF* output);
  /// Records each pixel's displacement (measurements: read_flow).
  void record_flow(bool on);

  /// The topology the overlay draws (scene key overlay = topology): of the
  /// field and surface of the step shown, found when it was first drawn;
  /// on a series, where the features are at this point of the step
  /// (topology_morph.h: those that persist move towards the next step's,
  /// with ids kept from step to step while played on); null before, or
  /// with another overlay.
  [[nodiscard]] const FlowTopology* overlay_topology() const {
    return overlay_ ? &overlay_topology_ : nullptr;
  }
  // ---- its images, read (rows bottom-up; IbfvsRenderer's reads)
  /// The displayed image F, RGBA 8-bit.
  [[nodiscard]] ImageU8 read_output() const { return renderer_->read_output(); }
  /// The same into `image` (its size), reusing its storage (a video's frames).
  void read_output(ImageU8& image) const { renderer_->read_output(image); }
  /// F_t as 16-bit-ready floats, RGBA (the texture image, --texture-out).
  [[nodiscard]] ImageF read_texture() const { return renderer_->read_texture(); }
  /// The surface's depth per pixel (1 where no surface is).
  [[nodiscard]] ImageF read_depth() const { return renderer_->read_depth(); }
  /// F_t and F as compositing takes them (take_composited).
  [[nodiscard]] ImageF read_texture_raw() const { return renderer_->read_texture_raw(); }
  [[nodiscard]] ImageF read_output_raw() const { return renderer_->read_output_raw(); }
  /// Whether the last frame left its contrast statistics to take_composited.
  [[nodiscard]] bool statistics_due() const { return renderer_->statistics_due(); }

  // ---- its images, drawn
  /// F scaled into the bound window's framebuffer (the viewer), `left`
  /// pixels kept for a panel.
  void present(int window_width, int window_height, int left = 0);
  /// F and its depth into a host's bound framebuffer, its viewport at
  /// `origin` the image's size (IbfvsRenderer::draw_to_host); the host's
  /// viewport is left as it was.
  void draw_to_host(glm::ivec2 origin, bool interior = false);
  /// Blocks until the GPU has finished every frame (a benchmark's clock).
  void finish();

 private:
  class StepPlayer;
  void load();
  // A new renderer with the settings in force: the texture carries over, or
  // with `restart` starts afresh (a new noise scale; a new seed).
  void rebuild(bool restart);
  // The scene's settings with the host's overrides (its colours, a drag's
  // advect view) onto the renderer; `upload`: the colour positions too.
  void apply_host(bool upload);
  // dt by the rule in force (dt()): the one place dt changes, called where
  // one of its inputs did (the step or dt key, the field, the camera, the
  // size, a host's view).
  void refit_dt();
  // The scene prepared again for `next`: from the source mesh or the files.
  void prepare_again(const Scene& next);
  // The GPU's part of the changes set() took for the next frame
  // (Apply::AtNextFrame): done before anything else draws.
  void settle();
  // The scene's overlay over the frame just drawn with `view`: its
  // features found again where the data, the step or the size changed.
  void draw_overlay(const ViewState& view);

  PreparedScene scene_;
  // What set() left the GPU for the next frame: a scene prepared again
  // (`carry`: the texture goes on over it), a new renderer (`restart`:
  // afresh), the settings, the field.
  struct Owed {
    bool load = false, carry = false, rebuild = false, restart = false, settings = false;
    bool field = false;
  } owed_;
  std::shared_ptr<const TriMesh> source_;  // the caller's mesh (null: the scene's files)
  std::string source_name_;
  std::unique_ptr<IbfvsRenderer> renderer_;
  std::unique_ptr<StepPlayer> player_;
  double time_ = 0.0;  // the last seek
  Camera camera_;
  std::optional<Camera> lock_camera_;
  float dt_ = 0.0f;
  std::optional<Camera> host_camera_;                   // fit_dt's
  std::optional<std::pair<double, float>> host_scale_;  // follow_host's (world per pixel, speed)
  std::optional<HostColours> host_colours_;
  std::optional<AdvectView> advect_override_;
  std::optional<float> probe_;
  bool defer_statistics_ = false, record_flow_ = false;
  std::unique_ptr<TopologyOverlay> overlay_;
  FlowTopology overlay_topology_;  // at the last frame's mix
  TopologyMorph overlay_morph_;
  // The features of the step shown and of the one played into.
  struct OverlaySteps {
    TopologyOptions options;  // the scene's when they were found
    std::size_t version = 0, step = 0, next = 0;
    FlowTopology first, second;
    int next_id = 0;  // carry_ids'
  };
  std::optional<OverlaySteps> overlay_steps_;
  std::size_t data_version_ = 0;  // a new field or surface: the overlay is found again
  std::optional<std::array<std::size_t, 5>> overlay_for_;  // version, step, next, width, height
  int frame_ = 0;
};

}  // namespace ibfvs
