// Sections: settings from the properties; after FXAA; one frame (the order
// of its steps); a page's layer. The texture itself (its settings by their
// keys' rules, frame pacing, the session, colours and dt) is the library's
// host unit, ibfvs::HostFlow, which PyVista's actor drives too. The surface
// and its colours, the processes' agreement and compositing, and ParaView's
// camera are units of their own (IBFVSSurface, IBFVSRanks, IBFVSView).
#include "vtkIBFVSMapper.h"

#include "IBFVSPage.h"
#include "IBFVSRanks.h"
#include "IBFVSSurface.h"
#include "IBFVSView.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/host_flow.h"
#include "ibfvs/render/session.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkWeakPointer.h"

vtkStandardNewMacro(vtkIBFVSMapper);

class vtkIBFVSMapper::Internals {
 public:
  // ---- the texture: settings (by each key's rule), frame pacing (Frames
  // Per Step), the session, colours and dt
  ibfvs::HostFlow flow;
  int association = 0;
  std::string vectors;

  // ---- the surface
  vtkMTimeType input_time = 0;
  vtkDataObject* input = nullptr;
  std::string input_vectors;
  bool cells_apart = false;              // coloured by a cell array: triangles apart
  std::shared_ptr<ibfvs::TriMesh> mesh;  // this rank's piece as taken; null: empty
  ibfvs::SplitMemory splits;             // its polygons' triangles, the same at every step
  std::string problem;                   // why this rank cannot draw the texture
  bool retake = true;                    // take the surface again (the vectors were set)
  std::string colour_key;  // the array, table and mode the flow's colours were mapped by

  // ---- the whole surface on process 0, for a page (SetGatherForPage)
  bool gather_for_page = false;
  std::shared_ptr<ibfvs::TriMesh> page_mesh;  // null: this process's own piece

  // ---- drawing
  vtkWeakPointer<vtkOpenGLRenderWindow> window;
  std::string warned;  // the last problem warned about
  std::string last_problem;

  // ---- the texture again after the renderer's FXAA (see RedrawAfterFXAA)
  vtkWeakPointer<vtkRenderer> observed;  // the renderer whose EndEvent we observe
  unsigned long observer = 0;
  bool redraw = false;      // this frame drew the texture, FXAA may blur it
  glm::ivec2 origin{0, 0};  // where it was drawn

  void StopObserving() {
    if (this->observed && this->observer) this->observed->RemoveObserver(this->observer);
    this->observed = nullptr;
    this->observer = 0;
  }

  ~Internals() {
    this->StopObserving();
    // Without a window to make current, the objects go with its context.
    if (this->flow.session() && this->window) {
      this->window->MakeCurrent();
      this->flow.release();
    }
  }
};

vtkIBFVSMapper::vtkIBFVSMapper() : Internal(new Internals) {}

vtkIBFVSMapper::~vtkIBFVSMapper() {
  delete this->Internal;
}

void vtkIBFVSMapper::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Vectors: " << this->Internal->vectors << "\n";
  os << indent << "Frame: " << this->Internal->flow.frame() << "\n";
}

void vtkIBFVSMapper::ReleaseGraphicsResources(vtkWindow* window) {
  if (this->Internal->flow.session()) {
    if (auto* w = vtkOpenGLRenderWindow::SafeDownCast(window)) {
      w->MakeCurrent();
      this->Internal->flow.release();
    }
  }
  this->Internal->flow.restart();
  this->Superclass::ReleaseGraphicsResources(window);
}

// ------------------------------------------------------------ settings

void vtkIBFVSMapper::SetVectors(int association, const char* name) {
  const std::string n = name ? name : "";
  if (n == this->Internal->vectors && association == this->Internal->association) return;
  this->Internal->vectors = n;
  this->Internal->association = association;
  this->Internal->retake = true;
  this->Modified();
}

// The scene with one property's value: checked by the keys' own rules and
// acted on by each changed key's (HostFlow::set_scene: live, a new noise
// grid, or a new start); a value the key refuses is an error, and the
// setting stays as it was.
void vtkIBFVSMapper::SetScene(const ibfvs::Scene& scene) {
  try {
    this->Internal->flow.set_scene(scene);
    this->Modified();
  } catch (const std::exception& e) {
    vtkErrorMacro(<< "IBFVS: " << e.what());
  }
}

// A property of a scene key, by its host name (SceneKey::host: ParaView's
// property and the representation's Set<Host> call it so): the value as
// the key's text (ibfvs::host_setting: within the key's range, an
// enumeration's nearest value), then the key's own check and rules.
bool vtkIBFVSMapper::SetKey(const char* host, double value) {
  const std::string name = host ? host : "";
  const ibfvs::SceneKey* key = ibfvs::find_host_key(name);
  if (!key) {
    vtkErrorMacro(<< "IBFVS: no setting is called '" << name << "'");
    return false;
  }
  ibfvs::Scene s = this->Internal->flow.scene();
  try {
    ibfvs::apply_setting(s, key->name, ibfvs::host_setting(*key, value));
  } catch (const ibfvs::SettingError& e) {
    vtkErrorMacro(<< "IBFVS: " << name << ": " << e.problem());
    return false;
  } catch (const std::exception& e) {
    vtkErrorMacro(<< "IBFVS: " << name << ": " << e.what());
    return false;
  }
  if (key->get(s) != key->get(this->Internal->flow.scene())) this->SetScene(s);
  return true;
}

void vtkIBFVSMapper::SetFramesPerStep(int frames) {
  const int v = std::clamp(frames, 1, ibfvs::kMaxFramesPerStep);
  if (this->Internal->flow.frames_per_step() == v) return;
  this->Internal->flow.set_frames_per_step(v);
  this->Modified();
}

void vtkIBFVSMapper::SetGatherForPage(int on) {
  this->Internal->gather_for_page = on != 0;
  if (!on) this->Internal->page_mesh.reset();
}

void vtkIBFVSMapper::Restart() {
  this->Internal->flow.restart();
  this->Modified();
}

int vtkIBFVSMapper::GetFrame() {
  return this->Internal->flow.frame();
}

const char* vtkIBFVSMapper::GetProblem() {
  return this->Internal->last_problem.c_str();
}

// ------------------------------------------------------------ after FXAA

// ParaView's views antialias by default with FXAA, an image-space filter the
// renderer runs over its whole picture after the opaque geometry: it takes
// the texture's one-pixel lines for jagged edges and blurs them (on the
// squareBend from above, 1024x768: A 0.986 -> 0.983, W 0.80 -> 0.86 px).
// The renderer's EndEvent comes after it; the mapper then draws the texture
// again where the surface is, within its silhouettes (those stay smoothed),
// behind whatever is nearer (the depth test against the host's depth); not
// while a volume is shown (drawn after the filter, without depth). Under MPI
// the compositing applies FXAA later, to the gathered image: not here.
void vtkIBFVSMapper::ObserveRenderer(vtkRenderer* ren) {
  Internals& in = *this->Internal;
  if (in.observed == ren) return;
  in.StopObserving();
  vtkNew<vtkCallbackCommand> callback;
  callback->SetClientData(this);
  callback->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    static_cast<vtkIBFVSMapper*>(self)->RedrawAfterFXAA();
  });
  in.observer = ren->AddObserver(vtkCommand::EndEvent, callback);
  in.observed = ren;
}

void vtkIBFVSMapper::RedrawAfterFXAA() {
  Internals& in = *this->Internal;
  if (!in.redraw) return;
  in.redraw = false;
  if (!in.flow.session() || !in.window || !in.observed) return;
  // Volumes are drawn after the filter and write no depth: drawing the
  // texture again would cover those in front of the surface.
  vtkVolumeCollection* volumes = in.observed->GetVolumes();
  vtkCollectionSimpleIterator it;
  volumes->InitTraversal(it);
  while (vtkVolume* volume = volumes->GetNextVolume(it))
    if (volume->GetVisibility()) return;
  // The filter leaves its own viewport; the texture is drawn at the frame's
  // (finish sets it and puts the filter's back).
  in.flow.finish(in.origin, true);
  in.window->GetState()->Reset();
}

// ------------------------------------------------------------ one frame

// This process's surface again (the data or the vectors changed); its
// colours and the flow's surface follow (GiveSurface).
void vtkIBFVSMapper::TakeSurface(vtkDataObject* input, vtkMTimeType input_time, bool cells_apart) {
  Internals& in = *this->Internal;
  in.retake = false;
  in.input = input;
  in.input_time = input_time;
  in.input_vectors = in.vectors;
  in.cells_apart = cells_apart;
  in.problem.clear();
  in.mesh = ibfvs::paraview::take_surface(input, in.vectors, cells_apart, in.splits, in.problem);
  in.colour_key.clear();
}

// The piece to the flow, with ParaView's colours at its vertices (positions
// in its table, the way the Surface representation maps them): the flow
// takes a change of content as new data (moved points carry the texture)
// and the same content again as nothing.
void vtkIBFVSMapper::GiveSurface(vtkActor* actor, const char* colour_array) {
  Internals& in = *this->Internal;
  if (!in.problem.empty()) return;
  if (!in.mesh) {
    in.flow.clear_surface();
    return;
  }
  ibfvs::TriMesh mesh = *in.mesh;
  ibfvs::HostColours colours;
  vtkScalarsToColors* lut = this->GetLookupTable();
  std::vector<float> t;
  if (ibfvs::paraview::map_colours(mesh, colour_array, lut, t, colours.table)) {
    mesh.scalars[ibfvs::kHostColour] = std::move(t);
    double diffuse[3];
    actor->GetProperty()->GetDiffuseColor(diffuse);
    colours.nan =
        ibfvs::paraview::nan_colour(lut).value_or(glm::vec3(diffuse[0], diffuse[1], diffuse[2]));
  } else {
    colours.table.clear();
  }
  try {
    in.flow.set_surface(std::move(mesh), "the input");
    in.flow.set_colours(std::move(colours));
  } catch (const std::exception& e) {
    in.problem = e.what();
  }
}

void vtkIBFVSMapper::Render(vtkRenderer* ren, vtkActor* actor) {
  Internals& in = *this->Internal;
  in.redraw = false;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  // Picking, and translucency (depth peeling draws a different number of
  // times on each rank): the plain surface, decided alike on every rank
  // before any collective.
  if (ren->GetSelector() || !window || actor->GetProperty()->GetOpacity() < 1.0) {
    in.last_problem = ren->GetSelector() ? "" : "IBFVS draws opaque surfaces (Opacity 1)";
    this->Superclass::Render(ren, actor);
    return;
  }
  in.window = window;

  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;

  // ---- this rank's surface (again only when the data or the vectors changed)
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  const vtkMTimeType input_time = input ? input->GetMTime() : 0;
  const char* colour_array = this->GetScalarVisibility() ? this->GetArrayName() : nullptr;
  const bool cells_apart =
      colour_array && *colour_array && ibfvs::paraview::colours_cells(this->GetScalarMode());
  // Not every frame while the surface cannot be drawn (bad vectors): taking
  // it is most of such a frame (motorbike: 500 ms against 120 for Surface).
  if (in.retake || input != in.input || input_time != in.input_time ||
      in.vectors != in.input_vectors || cells_apart != in.cells_apart) {
    this->TakeSurface(input, input_time, cells_apart);
  }
  // ---- its colours: again for a new surface, array, table or mode
  vtkScalarsToColors* lut = this->GetLookupTable();
  const std::string colour_key = std::string(colour_array ? colour_array : "") + "|" +
                                 std::to_string(lut ? lut->GetMTime() : 0) + "|" +
                                 std::to_string(this->GetScalarMode());
  if (colour_key != in.colour_key) {
    in.colour_key = colour_key;
    this->GiveSurface(actor, colour_array);
  }
  if (const int version = ibfvs::gl::current_gl_version(); in.problem.empty() && version < 45) {
    in.problem = "needs OpenGL 4.5 (this context has " + std::to_string(version / 10) + "." +
                 std::to_string(version % 10) + ")";
  }

  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  width = std::max(width, 1);
  height = std::max(height, 1);

  // ---- the ranks agree: all draw the texture or none, all take a change alike
  ibfvs::paraview::Agreement mine;
  mine.bad = !in.problem.empty();
  mine.changes = in.flow.pending(width, height);
  const ibfvs::paraview::Agreement all = ibfvs::paraview::agree(mine, controller);
  if (all.bad) {
    const std::string problem =
        !in.problem.empty()
            ? in.problem
            : std::string(
                  "another process's piece cannot be drawn with IBFVS (its warning says why)");
    if (problem != in.warned) {
      vtkWarningMacro(<< "IBFVS: " << problem << "; drawing the plain surface.");
      in.warned = problem;
    }
    in.last_problem = problem;
    in.flow.release();
    this->Superclass::Render(ren, actor);
    return;
  }
  in.warned.clear();
  in.last_problem.clear();

  // ---- a page of the view under MPI: every piece on process 0, with what
  // the page takes of it (the points, triangles, vectors, normals and the
  // array coloured by). Decided alike on every process (a property).
  in.page_mesh.reset();
  if (in.gather_for_page && ranks > 1) {
    ibfvs::TriMesh piece;
    if (in.mesh) {
      piece.positions = in.mesh->positions;
      piece.triangles = in.mesh->triangles;
      piece.vectors = in.mesh->vectors;
      piece.normals = in.mesh->normals;
      if (colour_array && *colour_array) {
        if (const auto a = in.mesh->scalars.find(colour_array); a != in.mesh->scalars.end())
          piece.scalars.insert(*a);
        if (const auto a = in.mesh->vector_arrays.find(colour_array);
            a != in.mesh->vector_arrays.end())
          piece.vector_arrays.insert(*a);
      }
    }
    in.page_mesh = std::make_shared<ibfvs::TriMesh>(
        ibfvs::paraview::gather_pieces(controller, in.mesh ? &piece : nullptr));
  }

  // ---- the session made, or taking on a new size, noise grid or data as
  // agreed (the texture goes on from where it is; only a restart starts
  // afresh), and its settings, colours and dt. The texture frames of this
  // render: one, and at a change of the data the frames the renders of the
  // last data fell short of Frames Per Step (ibfvs::FramePacer: Save
  // Animation gives each step all of them at its own data, Play and
  // Sequence mode one a render), all of them where the points moved under
  // a texture they do not carry (field_frame absolute).
  ibfvs::HostRender r;
  r.width = width;
  r.height = height;
  r.view = ibfvs::paraview::view_of(ren, actor);
  r.focal_distance = ren->GetActiveCamera()->GetDistance();
  double diffuse[3];
  actor->GetProperty()->GetDiffuseColor(diffuse);
  r.surface_color = glm::vec3(diffuse[0], diffuse[1], diffuse[2]);
  r.defer_statistics = ranks > 1;  // they wait for the composite
  const int frames = in.flow.begin(r, all.changes);
  // This rank still takes part in the compositing (as an empty piece); the
  // next frame's agreement turns every rank plain.
  if (!in.flow.problem().empty()) in.problem = in.flow.problem();

  // ---- the frames, each composited under MPI (every rank renders alike)
  for (int k = 0; k < frames; ++k) {
    in.flow.frame(r.view);
    if (ranks > 1) ibfvs::paraview::composite_frame(controller, in.flow.session(), width, height);
  }

  if (in.flow.session()) {
    in.origin = ibfvs::gl::viewport_origin();
    in.flow.finish(in.origin);
    this->ObserveRenderer(ren);
    in.redraw = ranks == 1 && ren->GetUseFXAA();
    // Whatever the library's calls left (pixel store, bindings it restored),
    // ParaView's state cache reads the context again.
    window->GetState()->Reset();
  }
}

// ------------------------------------------------------------ a page's layer

// The surface of the last render as a page takes it (vtkIBFVSPageExporter):
// the vectors, normals and ParaView's colours (positions in its table, as
// drawn) of the whole surface, moved by the actor's transform into world
// space. Only where the last render drew the texture.
bool vtkIBFVSMapper::TakePageLayer(vtkActor* actor, ibfvs::paraview::PageLayer& layer,
                                   std::string& problem) {
  Internals& in = *this->Internal;
  if (!in.last_problem.empty() || !in.problem.empty()) {
    problem = !in.last_problem.empty() ? in.last_problem : in.problem;
    return false;
  }
  // The whole surface gathered from every process, or this one's.
  const ibfvs::TriMesh* whole = in.page_mesh ? in.page_mesh.get() : in.mesh.get();
  if (!whole || whole->triangles.empty() || (!in.flow.session() && !in.page_mesh)) {
    problem = "it has drawn no texture (render the view first)";
    return false;
  }
  const ibfvs::TriMesh& drawn = *whole;
  ibfvs::TriMesh& m = layer.mesh;
  m = ibfvs::TriMesh{};
  m.positions = drawn.positions;
  m.triangles = drawn.triangles;
  m.vectors = drawn.vectors;
  m.normals = drawn.normals;
  layer.scene = in.flow.scene();
  layer.scene.frames_per_step = in.flow.frames_per_step();
  double colour[3];
  actor->GetProperty()->GetDiffuseColor(colour);
  layer.scene.surface_color = glm::vec3(colour[0], colour[1], colour[2]);
  // ParaView's colours as the render mapped them (the same function).
  layer.table.clear();
  const char* colour_array = this->GetScalarVisibility() ? this->GetArrayName() : nullptr;
  vtkScalarsToColors* lut = this->GetLookupTable();
  std::vector<float> t;
  if (ibfvs::paraview::map_colours(drawn, colour_array, lut, t, layer.table)) {
    m.scalars[ibfvs::paraview::kTableColour] = std::move(t);
    if (const std::optional<glm::vec3> nan = ibfvs::paraview::nan_colour(lut))
      layer.scene.surface_color = *nan;
  }
  layer.name = colour_array && *colour_array ? "coloured by " + std::string(colour_array)
                                             : "vectors " + in.vectors;
  // The actor's transform (Translation, Orientation, Scale) into the points,
  // the vectors and the normals.
  if (!actor->GetIsIdentity()) {
    const glm::mat4 a = ibfvs::paraview::to_glm(actor->GetMatrix());
    const glm::mat3 linear(a);
    const glm::mat3 normal = glm::transpose(glm::inverse(linear));
    for (glm::vec3& r : m.positions) r = glm::vec3(a * glm::vec4(r, 1.0f));
    for (glm::vec3& v : m.vectors) v = linear * v;
    for (glm::vec3& n : m.normals) {
      const glm::vec3 turned = normal * n;
      const float l = glm::length(turned);
      n = l > 0.0f ? turned / l : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  }
  // The fastest vector, in world space (the page's dt).
  layer.speed = 0.0f;
  for (const glm::vec3& v : m.vectors)
    if (const float l = glm::length(v); std::isfinite(l)) layer.speed = std::max(layer.speed, l);
  return true;
}
