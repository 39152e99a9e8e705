#pragma once
// A flow texture drawn into a host's own picture, one host render at a time:
// the unit a VTK mapper drives (PyVista's actor, python/ibfvs/pyvista.py).
// The host keeps its camera, its colour map and its other objects; each of
// its renders draws one texture frame (more at a change of the data:
// FramePacer) with the host's matrices, and the texture and its depth go
// into the host's framebuffer, behind whatever of the host's is nearer.
//
// Like Session, it needs the host's OpenGL 4.5 context current in every
// call that draws (render, release) and never makes one. It holds no GL
// object before the first render.

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/session.h"

namespace ibfvs {

/// The scalar array of a host's surface that holds, per vertex, its
/// position in the host's colour table (table_positions): the prepared mesh
/// carries it in its own vertex order.
inline constexpr const char* kHostColour = "ibfvs:colour";

/// A host's colours: its table at evenly spaced positions 0..1 (empty: the
/// plain surface colour) and the colour of values it cannot map (NaN).
struct HostColours {
  std::vector<glm::vec3> table;
  glm::vec3 nan{0.5f, 0.5f, 0.5f};
  bool operator==(const HostColours&) const = default;
};

/// One render of the host.
struct HostRender {
  int width = 1, height = 1;   ///< its viewport, pixels
  glm::ivec2 origin{0, 0};     ///< the viewport's lower left corner in its framebuffer
  ViewState view;              ///< its camera (and the actor's matrix) and projection
  double world_per_pixel = 0;  ///< world units a pixel spans at the focal point
  glm::vec3 surface_color{1.0f};
};

class HostFlow {
 public:
  HostFlow();
  /// Deletes the GL objects where their context is current; elsewhere they
  /// go with that context (release() first, where the host can).
  ~HostFlow();
  HostFlow(const HostFlow&) = delete;
  HostFlow& operator=(const HostFlow&) = delete;

  /// The texture keys of `scene` (alpha, beta, scale, step, seed, ...): by
  /// each changed key's rule (change_effect) live on the running texture, a
  /// new noise grid under it, or a new start (a new seed). Throws
  /// SettingError for a value that is not valid, changing nothing.
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
  void set_colours(HostColours colours);
  /// Starts the texture afresh from noise at the next render.
  void restart();

  /// One host render: the frames it owes and the texture into the bound
  /// framebuffer at `r.origin`. The host's state is left as it was but for
  /// what a draw writes (its state cache must read the context again).
  void render(const HostRender& r);
  /// Drops the GL objects (the host's context current); the next render
  /// starts afresh.
  void release();

  /// Texture frames since the texture last started afresh.
  [[nodiscard]] int frame() const { return frame_; }
  [[nodiscard]] bool has_surface() const { return mesh_ != nullptr; }
  /// The running session (null before the first render).
  [[nodiscard]] const Session* session() const { return session_.get(); }

 private:
  void update_session(int width, int height);
  void apply_settings(const HostRender& r);

  Scene scene_;
  FramePacer pacer_;
  std::shared_ptr<const TriMesh> mesh_;
  std::string name_;
  float speed_ = 0.0f;  // the fastest vector
  HostColours colours_;
  std::unique_ptr<Session> session_;
  const void* made_in_ = nullptr;  // the context the session's objects are in
  int width_ = 0, height_ = 0;
  int frame_ = 0;
  bool restart_ = true, regrid_ = false, settings_changed_ = false;
  bool data_changed_ = false, points_moved_ = false, colours_changed_ = true;
};

}  // namespace ibfvs
