// A preparation's field: the field spec in force, its vectors, and the data of each step of an
// unsteady scene.
#include <string>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/geometry/vertex_scalar.h"
#include "steps.h"

namespace ibfvs::prep {

void field(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  TriMesh& mesh = *c.mesh;
  const std::string& mesh_label = c.label;
  std::optional<FieldSpec>& field_spec = c.field_spec;
  const std::optional<FieldSpec>& default_field = c.default_field;
  const LoadedMesh& loaded = c.loaded;
  const glm::vec3 up = c.up;
  const bool series = c.series;
  const std::size_t series_first = c.series_first, series_last = c.series_last;
  if (!field_spec) {
    field_spec = mesh.vectors.size() == mesh.positions.size() || !mesh.vector_arrays.empty()
                     ? FieldSpec::parse("file")
                 : default_field                              ? *default_field
                 : loaded.generated_landscape ? [&] {
                     FieldSpec g = FieldSpec::parse("gradient:down");
                     g.value = up;
                     return g;
                   }()
                                              : FieldSpec::parse("rotate:0,1,0");
  }
  const TangentMode tangent = s.tangent;
  // The data at a step on this mesh: a series' surfaces (points that move,
  // triangles that change), another file's arrays, a field at another time.
  StepContext context;
  context.mesh = c.mesh;
  context.still = c.still;
  context.order = loaded.vertex_order;
  context.source_vertices = loaded.file_vertices;
  context.source_topology = loaded.file_topology;
  context.spec = *field_spec;
  context.tangent = tangent;
  context.reverse = s.reverse;
  context.color_by = s.color_by;
  context.beta_by = s.beta_by;
  if (!s.field_steps.empty()) {
    // An unsteady field: its steps, evaluated when the animation reaches them.
    p.step_count = s.field_steps.size();
    p.step_data = [files = s.field_steps, expected = loaded.file_vertices, blocks = s.blocks,
                   context](std::size_t k) {
      const std::string& file = files[k];
      TriMesh step = read_any_mesh(file, blocks);
      if (step.vertex_count() != expected)
        throw SettingError("field_step", file + ": " + std::to_string(step.vertex_count()) +
                                             " vertices, the mesh has " + std::to_string(expected));
      try {
        return step_on_mesh(context, std::move(step), file, true);
      } catch (const InputError& e) {
        throw SettingError("field_step", e.what());
      }
    };
  } else if (series && series_last > series_first && !own_time(*field_spec)) {
    // A series plays whatever the field: a moving mesh's points move with a
    // field of the scene's (rotate:, principal:) as with its own arrays.
    p.step_count = series_last - series_first + 1;
    p.step_data = [read = loaded.read_step, first = series_first, context,
                   label = mesh_label](std::size_t k) {
      const std::string where = label + ": step " + std::to_string(first + k);
      try {
        return step_on_mesh(context, read(first + k), where);
      } catch (const SettingError&) {
        throw;
      } catch (const InputError& e) {
        const std::string what = e.what();
        throw SettingError("field", what.rfind(where, 0) == 0 ? what : where + ": " + what);
      }
    };
  } else if (s.time && s.time->last > s.time->first) {
    p.step_count = s.time->last - s.time->first + 1;
    if (field_spec->kind == FieldKind::Wind)
      read_lonlat_grid(field_spec->path, field_spec->east, s.time->last);  // the range exists
    p.step_data = [context, first = s.time->first](std::size_t k) {
      StepData d;
      FieldSpec at = context.spec;
      at.time = first + k;
      d.field = evaluate_field(*context.mesh, at, context.tangent);
      if (context.reverse)
        for (glm::vec3& v : d.field) v = -v;
      if (!context.color_by.empty())
        d.color_scalar = vertex_scalar(*context.mesh, d.field, context.color_by);
      if (!context.beta_by.empty())
        d.beta_scalar = vertex_scalar(*context.mesh, d.field, context.beta_by);
      return d;
    };
  }
  if (p.step_data) p.step_data = cached_steps(std::move(p.step_data), p.step_count);
  FieldReport field_report;
  try {
    if (p.step_data) {
      p.field = p.step_data(0).field;
    } else {
      p.field = evaluate_field(mesh, *field_spec, tangent, &field_report);
      if (s.reverse)
        for (glm::vec3& x : p.field) x = -x;
    }
  } catch (const SettingError&) {
    throw;
  } catch (const InputError& e) {
    throw SettingError("field", mesh_label + ": " + e.what());
  }
  // A netCDF field's steps by their dates.
  if (field_spec->kind == FieldKind::Wind) {
    const std::size_t first = s.time ? s.time->first : 0;
    p.step_labels = for_key("field", [&] {
      return time_labels(netcdf_time_axis(field_spec->path, field_spec->east), first,
                         first + p.step_count - 1);
    });
  }
  if (field_report.outside_volume > 0)
    p.warnings.push_back(field_spec->path + ": " + std::to_string(field_report.outside_volume) +
                         " of " + std::to_string(mesh.vertex_count()) +
                         " vertices lie outside the volume (their vectors are zero)");
  if (field_report.non_finite_zeroed > 0)
    p.warnings.push_back(mesh_label + ": " + std::to_string(field_report.non_finite_zeroed) +
                         " vectors were NaN or infinite and are set to zero");
}

}  // namespace ibfvs::prep
