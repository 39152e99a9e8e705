// A host's time steps as one unsteady scene (prepare_states): the first
// state prepared, each later one a step on it.

#include <memory>

#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {

PreparedScene prepare_states(const Scene& scene, std::vector<TriMesh> states,
                             const std::string& name) {
  if (states.empty()) throw InputError(name + ": no time steps to show");
  const std::size_t count = states.size();
  PreparedScene p = prepare_scene(scene, std::move(states[0]), name);
  if (count == 1) return p;
  auto steps = std::make_shared<std::vector<StepData>>(count);
  StepData& first = (*steps)[0];
  first.field = p.field;
  first.color_scalar = p.color_scalar;
  first.beta_scalar = p.beta_scalar;
  for (std::size_t k = 1; k < count; ++k) {
    const std::string where = name + ": step " + std::to_string(k);
    PreparedScene next = prepare_change(p, std::move(states[k]), where);
    states[k] = TriMesh{};  // its memory back as the steps go
    StepData& d = (*steps)[k];
    d.field = std::move(next.field);
    d.color_scalar = std::move(next.color_scalar);
    d.beta_scalar = std::move(next.beta_scalar);
    if (next.mesh->triangles != p.mesh->triangles) {
      d.mesh = next.mesh;  // prepared afresh: triangles of its own
    } else if (next.mesh->positions != p.mesh->positions) {
      d.positions = next.mesh->positions;
      d.normals = next.mesh->normals;
    }
  }
  p.step_count = count;
  p.step_labels.clear();  // a host's states: their times are the host's
  p.step_data = [steps](std::size_t k) {
    if (k >= steps->size()) throw InputError("no time step " + std::to_string(k));
    return (*steps)[k];
  };
  // dt and the fastest vertex over the steps played, not the first alone.
  return resized(p, p.width, p.height);
}

}  // namespace ibfvs
