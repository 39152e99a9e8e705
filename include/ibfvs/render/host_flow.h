#pragma once
// A flow texture drawn into a host's own picture, one host render at a time:
// the unit both VTK mappers drive (PyVista's actor, python/ibfvs/pyvista.py;
// ParaView's representation, paraview/IBFVS/Representations/vtkIBFVSMapper).
// The host keeps its camera, its colour map and its other objects; each of
// its renders draws one texture frame (more at a change of the data:
// FramePacer) with the host's matrices, and the texture and its depth go
// into the host's framebuffer, behind whatever of the host's is nearer.
//
// Like Session, it needs the host's OpenGL 4.5 context current in every
// call that draws (render, release) and never makes one. It holds no GL
// object before the first render.
//
// A host of several processes (ParaView under MPI), each with its piece of
// the surface, renders in steps: pending() says what this process's flow
// owes, the host agrees it across the processes (any flag, the fastest
// vector, the bounds of every piece), begin() takes the agreement, and
// between the frames (frame()) the host composites the texture images;
// finish() draws. render() is those steps for one process.

#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/session.h"

namespace ibfvs {

/// One render of the host.
struct HostRender {
  int width = 1, height = 1;  ///< its viewport, pixels
  glm::ivec2 origin{0, 0};    ///< the viewport's lower left corner in its framebuffer
  ViewState view;             ///< its camera (and the actor's matrix) and projection
  /// World units from the camera to its focal point (perspective: where
  /// world_per_pixel measures a pixel; ignored for a parallel projection).
  double focal_distance = 0;
  glm::vec3 surface_color{1.0f};
  /// The contrast statistics wait for the host (it composites the images
  /// of several processes first).
  bool defer_statistics = false;
};

/// What a flow owes before a render: for several processes, each one's,
/// agreed into one (any flag of any, the fastest vector, the bounds of all
/// pieces) that they all take alike.
struct HostChanges {
  bool restart = false;  ///< the texture starts afresh (a restart, a first surface)
  bool resize = false;   ///< the view's size changed
  bool changed = false;  ///< the surface changed
  bool moved = false;    ///< and its points moved
  float speed = 0.0f;    ///< the fastest vector
  /// The surface's bounds (lower, upper); none for an empty piece.
  std::optional<std::pair<glm::vec3, glm::vec3>> bounds;
  /// The length of the bounds' diagonal (0 without bounds).
  [[nodiscard]] float diagonal() const;
};

class HostFlow {
 public:
  HostFlow();
  /// Deletes the GL objects where their context is current; elsewhere they
  /// go with that context (release() first, where the host can).
  ~HostFlow();
  HostFlow(const HostFlow&) = delete;
  HostFlow& operator=(const HostFlow&) = delete;

  /// The keys of `scene` (alpha, beta, scale, step, seed, ...), through the
  /// session's one door now (Session::set: checked, planned and taken once,
  /// the scene prepared again there where a key needs it; its GPU part at
  /// the next render, where the host's context is current). Before the
  /// first render they are checked (scene_settings) and the first session
  /// is made with them. Throws SettingError for a value that is not valid,
  /// changing nothing.
  void set_scene(const Scene& scene);
  [[nodiscard]] const Scene& scene() const { return scene_; }
  /// At least this many texture frames for each change of the surface
  /// (FramePacer, clamped to 1..kMaxFramesPerStep).
  void set_frames_per_step(int frames);
  /// The surface with its vectors, and the colour positions as the scalar
  /// kHostColour where it is coloured. Checked at once: throws InputError
  /// naming `name` for a mesh that cannot be drawn. The same content again
  /// changes nothing; moved points (the same triangles) move the texture
  /// with them (field_frame surface), anything else is new data the
  /// texture goes on over.
  void set_surface(TriMesh mesh, const std::string& name);
  /// No surface: this process's piece is empty (it still takes part in the
  /// host's frames); render() refuses.
  void clear_surface();
  void set_colours(HostColours colours);
  /// Starts the texture afresh from noise at the next render.
  void restart();

  /// One host render: the frames it owes and the texture into the bound
  /// framebuffer at `r.origin`. The host's state is left as it was but for
  /// what a draw writes (its state cache must read the context again).
  void render(const HostRender& r);

  /// The render in steps, for a host of several processes. What this
  /// flow owes a render of width x height.
  [[nodiscard]] HostChanges pending(int width, int height) const;
  /// The session made, or taking on the agreed changes, and its settings,
  /// colours and dt; returns the texture frames of this render (FramePacer,
  /// the same in every process that takes the same agreement). A surface
  /// the texture cannot take leaves no session, problem() saying why: the
  /// host still calls frame() as often.
  int begin(const HostRender& r, const HostChanges& agreed);
  /// One texture frame (none drawn without a session).
  void frame(const ViewState& view);
  /// The texture and its depth into the bound framebuffer at `origin`;
  /// `within_surface`: only where the host's picture already shows the
  /// surface (again after an image filter over the host's picture).
  void finish(glm::ivec2 origin, bool within_surface = false);

  /// Drops the GL objects (the host's context current); the next render
  /// starts afresh.
  void release();

  /// Texture frames since the texture last started afresh.
  [[nodiscard]] int frame() const { return frame_; }
  [[nodiscard]] int frames_per_step() const { return pacer_.frames_per_step(); }
  /// Why the last begin() left no session with a surface to draw; empty otherwise.
  [[nodiscard]] const std::string& problem() const { return problem_; }
  /// The running session (null before the first render, for an empty
  /// piece, or after a problem): a host composites its images.
  [[nodiscard]] const Session* session() const { return session_.get(); }
  [[nodiscard]] Session* session() { return session_.get(); }

 private:
  void update_session(int width, int height, const HostChanges& agreed);
  void apply_host(const HostRender& r, const HostChanges& agreed);

  Scene scene_;
  FramePacer pacer_;
  std::shared_ptr<const TriMesh> mesh_;
  std::string name_;
  float speed_ = 0.0f;  // the fastest vector
  std::pair<glm::vec3, glm::vec3> bounds_{};
  std::string problem_;
  std::exception_ptr failure_;  // what left no session at the last begin()
  HostColours colours_;
  std::unique_ptr<Session> session_;
  const void* made_in_ = nullptr;  // the context the session's objects are in
  int width_ = 0, height_ = 0;
  int frame_ = 0;
  // The host's own: a restart asked for, and its piece changed (moved).
  bool restart_ = true, data_changed_ = false, points_moved_ = false;
};

}  // namespace ibfvs
