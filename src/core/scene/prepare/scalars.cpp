// A preparation's scalars: on the surface (netCDF grids, curvature, the displacement they drive),
// and for colour and beta with their ranges (and the surface image).
#include <cmath>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/geometry/vertex_scalar.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/image/image.h"
#include "steps.h"

namespace ibfvs::prep {

void surface_scalars(Preparation& c) {
  const Scene& s = c.s;
  TriMesh& mesh = *c.mesh;
  const std::string& mesh_label = c.label;
  std::optional<FieldSpec>& field_spec = c.field_spec;
  const std::optional<FieldSpec>& default_field = c.default_field;
  // ---- scalars sampled from netCDF grids
  for (const GridScalar& g : s.scalars) {
    LonLatGrid grid = read_lonlat_grid(g.path, g.variable, 0);
    if (grid.time_steps > 1) grid = read_lonlat_grid(g.path, g.variable, c.time_first);
    mesh.scalars[g.name] = lonlat_scalars(mesh, grid);
  }

  // ---- curvature, once, when the field or a scalar needs it
  {
    const bool principal =
        (field_spec && field_spec->kind == FieldKind::Principal) ||
        (!field_spec && default_field && default_field->kind == FieldKind::Principal);
    if ((principal || wants_curvature(s.color_by) || wants_curvature(s.beta_by) ||
         (s.displace && wants_curvature(s.displace->scalar))) &&
        !mesh.scalars.count("kmax"))
      store_curvature(mesh, compute_curvature(mesh), false);
  }

  // ---- displacement along the normals (the vertical scale of a relief)
  if (s.displace) {
    if (!std::isfinite(s.displace->factor))
      throw SettingError("displace", "the factor must be a finite number");
    std::vector<float> amount;
    try {
      amount = vertex_scalar(mesh, {}, s.displace->scalar);
    } catch (const InputError& e) {
      throw SettingError("displace", mesh_label + ": " + e.what());
    }
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      if (std::isfinite(amount[i]))
        mesh.positions[i] += s.displace->factor * amount[i] * mesh.normals[i];
    compute_vertex_normals(mesh);
  }
}

void colours(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  TriMesh& mesh = *c.mesh;
  const std::string& mesh_label = c.label;
  RenderSettings& settings = p.settings;
  // ---- scalars for colour and beta, and their ranges
  const auto scalar_range = [&](const std::string& name, const char* key,
                                const std::optional<ScalarRange>& range, const char* range_key,
                                std::vector<float>& values, bool colour) {
    try {
      values = vertex_scalar(mesh, p.field, name);
    } catch (const InputError& e) {
      throw SettingError(key, mesh_label + ": " + e.what());
    }
    // Percentiles of the steps played (a run from rest has none at the first).
    std::vector<float> all;
    if (p.step_data && p.step_count > 1 && (!range || range->percentile)) {
      all = values;
      for (std::size_t k = 1; k < steps_played(p); ++k) {
        const StepData d = p.step_data(k);
        const std::vector<float>& v = colour ? d.color_scalar : d.beta_scalar;
        all.insert(all.end(), v.begin(), v.end());
      }
    }
    const std::vector<float>& sample = all.empty() ? values : all;
    if (!range) return quantile_range(sample);
    if (range->percentile) return quantile_range(sample, range->lo / 100.0f, range->hi / 100.0f);
    if (!(range->hi > range->lo)) throw SettingError(range_key, "expected LO < HI");
    return glm::vec2(range->lo, range->hi);
  };
  if (!s.color_by.empty()) {
    settings.use_color = true;
    settings.color_range =
        scalar_range(s.color_by, "color_by", s.color_range, "color_range", p.color_scalar, true);
  }
  if (!s.beta_by.empty()) {
    settings.use_beta = true;
    settings.beta_range =
        scalar_range(s.beta_by, "beta_by", s.beta_range, "beta_range", p.beta_scalar, false);
  }
  settings.validate();

  // ---- the surface image, read once
  if (!s.surface_image.empty())
    p.surface_image = for_key("surface_image", [&] { return read_png(s.surface_image); });
}

}  // namespace ibfvs::prep
