#include "ibfvs/core/fields/vector_field.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {

namespace {

// The optional parts of principal: and gradient: (a vector and one flag word).
void parse_options(const std::string& s, const std::vector<std::string>& parts, const char* flag,
                   bool& flag_value, glm::vec3& vector, bool& vector_given) {
  for (std::size_t i = 2; i < parts.size(); ++i) {
    if (parts[i] == flag) {
      flag_value = true;
    } else if (parts[i].find(',') != std::string::npos) {
      vector = parse_vec3(parts[i]);
      vector_given = true;
      if (glm::length(vector) == 0.0f)
        throw InputError("the vector in '" + s + "' must not be zero");
    } else {
      throw InputError("unknown part '" + parts[i] + "' in '" + s + "' (expected X,Y,Z or " + flag +
                       ")");
    }
  }
}

}  // namespace

std::string describe_arrays(const TriMesh& mesh) {
  std::vector<std::pair<std::string, int>> all;
  if (mesh.vectors.size() == mesh.positions.size() && !mesh.vectors.empty())
    all.emplace_back("vx vy vz", 3);
  for (const auto& [name, v] : mesh.vector_arrays) all.emplace_back(name, 3);
  for (const auto& [name, v] : mesh.scalars) all.emplace_back(name, 1);
  for (const auto& [name, c] : mesh.other_arrays) all.emplace_back(name, c);
  if (all.empty()) return "none";
  std::string out;
  for (const auto& [name, c] : all)
    out += (out.empty() ? "" : ", ") + name + " (" + std::to_string(c) + ")";
  return out;
}

const std::vector<glm::vec3>& file_vectors(const TriMesh& mesh, const std::string& name) {
  const std::size_t n = mesh.vertex_count();
  if (name.empty()) {
    if (mesh.vectors.size() == n && n > 0) return mesh.vectors;
    if (mesh.vector_arrays.size() == 1) return mesh.vector_arrays.begin()->second;
    if (mesh.vector_arrays.empty())
      throw InputError(
          "file: the mesh has no per-vertex vectors (PLY vx vy vz or a 3-component array); its "
          "arrays: " +
          describe_arrays(mesh));
    throw InputError("file: the mesh has " + std::to_string(mesh.vector_arrays.size()) +
                     " vector arrays; name one with file:NAME (arrays: " + describe_arrays(mesh) +
                     ")");
  }
  if (const auto it = mesh.vector_arrays.find(name); it != mesh.vector_arrays.end())
    return it->second;
  if (mesh.scalars.count(name))
    throw InputError("file:" + name + ": the array has 1 component; a field needs 3");
  if (const auto it = mesh.other_arrays.find(name); it != mesh.other_arrays.end())
    throw InputError("file:" + name + ": the array has " + std::to_string(it->second) +
                     " components; a field needs 3");
  throw InputError("file:" + name + ": no such array (arrays: " + describe_arrays(mesh) + ")");
}

namespace {

using Parts = std::vector<std::string>;

void parse_file(FieldSpec& spec, const Parts&, const std::string& s) {
  if (s.size() > 5) spec.array = s.substr(5);  // after "file:", colons and all
}

void parse_sample(FieldSpec& spec, const Parts& parts, const std::string& s) {
  if (parts.size() < 3 || parts.size() > 4 || parts[1].empty() || parts[2].empty())
    throw InputError("expected sample:FILE:NAME[:OFFSET], got '" + s + "'");
  spec.path = parts[1];
  spec.array = parts[2];
  if (parts.size() == 4) {
    const double offset = parse_number(parts[3]);
    if (!std::isfinite(offset)) throw InputError("the offset in '" + s + "' must be finite");
    spec.offset = static_cast<float>(offset);
  }
}

void parse_elements(FieldSpec& spec, const Parts& parts, const std::string& s) {
  spec.value = parts.size() > 1 ? parse_vec3(parts[1]) : glm::vec3(0.0f);
  if (parts.size() > 2) throw InputError("expected elements[:X,Y,Z], got '" + s + "'");
}

void parse_principal(FieldSpec& spec, const Parts& parts, const std::string& s) {
  if (parts.size() < 2 || (parts[1] != "min" && parts[1] != "max"))
    throw InputError("expected principal:min or principal:max, got '" + s + "'");
  spec.use_max = parts[1] == "max";
  spec.value = glm::vec3(0, 1, 0);
  Parts rest;
  for (const std::string& part : parts) {
    if (part.rfind("smooth=", 0) != 0) {
      rest.push_back(part);
      continue;
    }
    try {
      spec.smooth = static_cast<int>(parse_integer(std::string_view(part).substr(7), 0, 1000));
    } catch (const InputError& e) {
      throw InputError("smooth in '" + s + "': " + e.what());
    }
  }
  parse_options(s, rest, "rot90", spec.rotate90, spec.value, spec.vector_given);
}

void parse_wind(FieldSpec& spec, const Parts& parts, const std::string& s) {
  if (parts.size() != 2 && parts.size() != 4)
    throw InputError("expected wind:FILE or wind:FILE:UVAR:VVAR, got '" + s + "'");
  spec.path = parts[1];
  if (parts.size() == 4) spec.east = parts[2], spec.north = parts[3];
  if (spec.path.empty() || spec.east.empty() || spec.north.empty())
    throw InputError("empty file or variable name in '" + s + "'");
}

void parse_gradient(FieldSpec& spec, const Parts& parts, const std::string& s) {
  if (parts.size() < 2 || (parts[1] != "down" && parts[1] != "up"))
    throw InputError("expected gradient:down or gradient:up, got '" + s + "'");
  spec.downhill = parts[1] == "down";
  spec.value = glm::vec3(0, 1, 0);
  parse_options(s, parts, "normalize", spec.normalize, spec.value, spec.vector_given);
}

// uniform:X,Y,Z and rotate:X,Y,Z.
void parse_vector(FieldSpec& spec, const Parts&, const std::string& s) {
  const std::size_t colon = s.find(':');
  if (colon == std::string::npos) throw InputError("expected " + s + ":X,Y,Z, got '" + s + "'");
  spec.value = parse_vec3(std::string_view(s).substr(colon + 1));
  if (spec.kind == FieldKind::Rotate && glm::length(spec.value) == 0.0f)
    throw InputError("the rotation axis must not be zero");
}

// The fields by the name before their first colon, and how each is written.
struct FieldForm {
  std::string_view name;
  FieldKind kind;
  std::string_view form;
  void (*parse)(FieldSpec& spec, const Parts& parts, const std::string& text);
};
constexpr FieldForm kForms[] = {
    {"file", FieldKind::File, "file[:NAME]", parse_file},
    {"uniform", FieldKind::Uniform, "uniform:X,Y,Z", parse_vector},
    {"rotate", FieldKind::Rotate, "rotate:X,Y,Z", parse_vector},
    {"elements", FieldKind::Elements, "elements", parse_elements},
    {"principal", FieldKind::Principal, "principal:min|max", parse_principal},
    {"gradient", FieldKind::Gradient, "gradient:down|up", parse_gradient},
    {"wind", FieldKind::Wind, "wind:FILE", parse_wind},
    {"sample", FieldKind::Sample, "sample:FILE:NAME", parse_sample},
};

}  // namespace

FieldSpec FieldSpec::parse(std::string_view text) {
  const std::string s(text);
  const std::string name = s.substr(0, s.find(':'));
  for (const FieldForm& f : kForms) {
    if (f.name != name) continue;
    FieldSpec spec;
    spec.kind = f.kind;
    f.parse(spec, split_colons(s), s);
    return spec;
  }
  std::string forms;
  for (const FieldForm& f : kForms) {
    if (!forms.empty()) forms += ", ";
    forms += f.form;
  }
  throw InputError("unknown field '" + s + "' (expected " + forms + ")");
}

std::string FieldSpec::text() const {
  const std::string v = format_vec3(value);
  switch (kind) {
    case FieldKind::File:
      return array.empty() ? "file" : "file:" + array;
    case FieldKind::Sample:
      return "sample:" + path + ":" + array + (offset != 0.0f ? ":" + format_number(offset) : "");
    case FieldKind::Uniform:
      return "uniform:" + v;
    case FieldKind::Rotate:
      return "rotate:" + v;
    case FieldKind::Elements:
      return value == glm::vec3(0.0f) ? "elements" : "elements:" + v;
    case FieldKind::Principal:
      return std::string("principal:") + (use_max ? "max" : "min") + (vector_given ? ":" + v : "") +
             (rotate90 ? ":rot90" : "") + (smooth > 0 ? ":smooth=" + std::to_string(smooth) : "");
    case FieldKind::Gradient:
      return std::string("gradient:") + (downhill ? "down" : "up") + (vector_given ? ":" + v : "") +
             (normalize ? ":normalize" : "");
    case FieldKind::Wind:
      return "wind:" + path + (east != "UWND" || north != "VWND" ? ":" + east + ":" + north : "");
  }
  return "file";
}

std::string FieldSpec::to_string() const {
  std::ostringstream out;
  const auto vec = [&] { out << value.x << "," << value.y << "," << value.z; };
  switch (kind) {
    case FieldKind::File:
    case FieldKind::Sample:
      return text();
    case FieldKind::Uniform:
      out << "uniform:";
      vec();
      break;
    case FieldKind::Rotate:
      out << "rotate:";
      vec();
      break;
    case FieldKind::Elements:
      out << "elements:";
      vec();
      out << " with " << elements.size() << " element" << (elements.size() == 1 ? "" : "s");
      break;
    case FieldKind::Principal:
      out << "principal:" << (use_max ? "max" : "min") << ":";
      vec();
      if (rotate90) out << ":rot90";
      if (smooth > 0) out << ":smooth=" << smooth;
      break;
    case FieldKind::Gradient:
      out << "gradient:" << (downhill ? "down" : "up") << ":";
      vec();
      if (normalize) out << ":normalize";
      break;
    case FieldKind::Wind:
      out << "wind:" << path << ":" << east << ":" << north << " at time index " << time;
      break;
  }
  return out.str();
}

std::vector<glm::vec3> evaluate_field(const TriMesh& mesh, const FieldSpec& spec, TangentMode mode,
                                      FieldReport* report_out) {
  FieldReport report;
  const std::size_t n = mesh.vertex_count();
  std::vector<glm::vec3> v(n);
  switch (spec.kind) {
    case FieldKind::File:
      v = file_vectors(mesh, spec.array);
      break;
    case FieldKind::Sample: {
      // Near-wall flow: each vertex moved `offset` along its normal; where
      // that point lies outside the volume (the normal points into the
      // body), against it.
      if (spec.offset != 0.0f && mesh.normals.size() != n)
        throw InputError("sampling off the surface needs vertex normals");
      std::vector<glm::vec3> points(n);
      for (std::size_t i = 0; i < n; ++i)
        points[i] = mesh.positions[i] +
                    (spec.offset != 0.0f ? spec.offset * mesh.normals[i] : glm::vec3(0.0f));
      VolumeSample sample = sample_volume(spec.path, spec.array, spec.time, points);
      std::vector<glm::vec3> retry_points;
      std::vector<std::size_t> retry;
      for (std::size_t i = 0; i < n; ++i)
        if (!sample.found[i] && spec.offset != 0.0f) {
          retry.push_back(i);
          retry_points.push_back(mesh.positions[i] - spec.offset * mesh.normals[i]);
        }
      if (!retry.empty()) {
        const VolumeSample again = sample_volume(spec.path, spec.array, spec.time, retry_points);
        for (std::size_t k = 0; k < retry.size(); ++k)
          if (again.found[k]) {
            sample.values[retry[k]] = again.values[k];
            sample.found[retry[k]] = 1;
          }
      }
      for (std::size_t i = 0; i < n; ++i) {
        v[i] = sample.found[i] ? sample.values[i] : glm::vec3(0.0f);
        if (!sample.found[i]) ++report.outside_volume;
      }
      if (n > 0 && report.outside_volume == n)
        throw InputError(spec.path +
                         ": no vertex lies inside the volume (is it the right "
                         "dataset, and the offset small enough?)");
      break;
    }
    case FieldKind::Uniform:
      std::fill(v.begin(), v.end(), spec.value);
      break;
    case FieldKind::Rotate: {
      const glm::vec3 c = mesh_bounds(mesh).centre();
      for (std::size_t i = 0; i < n; ++i) v[i] = glm::cross(spec.value, mesh.positions[i] - c);
      break;
    }
    case FieldKind::Elements: {
      PotentialFlow flow{spec.value, spec.elements};
      for (std::size_t i = 0; i < n; ++i) v[i] = flow.velocity(mesh.positions[i]);
      break;
    }
    case FieldKind::Principal: {
      const Curvature c = mesh_curvature(mesh);
      const std::vector<glm::vec3> dirs =
          smooth_line_field(mesh, c.normal, spec.use_max ? c.dmax : c.dmin, spec.smooth);
      for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 d = dirs[i];
        // The sign rule of section 4.2: along the user vector, where the
        // direction is not (nearly) perpendicular to it.
        if (glm::dot(d, spec.value) < 0.0f) d = -d;
        v[i] = spec.rotate90 ? glm::cross(c.normal[i], d) : d;
      }
      break;
    }
    case FieldKind::Wind: {
      const LonLatGrid u = read_lonlat_grid(spec.path, spec.east, spec.time);
      const LonLatGrid w = read_lonlat_grid(spec.path, spec.north, spec.time);
      try {
        v = lonlat_vectors(mesh, u, w);
      } catch (const InputError& e) {
        throw InputError(spec.path + ": " + e.what());
      }
      break;
    }
    case FieldKind::Gradient: {
      if (mesh.normals.size() != n) throw InputError("the gradient field needs vertex normals");
      const glm::vec3 up = glm::normalize(spec.value);
      for (std::size_t i = 0; i < n; ++i) {
        // Steepest ascent of h = up . r on the surface: up minus its normal part.
        const glm::vec3& nrm = mesh.normals[i];
        glm::vec3 g = up - glm::dot(up, nrm) * nrm;
        if (spec.downhill) g = -g;
        const float len = glm::length(g);
        if (spec.normalize) g = len > 1e-6f ? g / len : glm::vec3(0.0f);
        v[i] = g;
      }
      break;
    }
  }
  for (glm::vec3& x : v) {
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) {
      x = glm::vec3(0.0f);
      ++report.non_finite_zeroed;
    }
  }
  if (n > 0 && report.non_finite_zeroed == n)
    throw InputError("the vector field has no finite vector at all (every one is NaN or infinite)");
  if (mode == TangentMode::Project) {
    if (mesh.normals.size() != n) throw InputError("projection needs vertex normals");
    for (std::size_t i = 0; i < n; ++i) v[i] -= glm::dot(v[i], mesh.normals[i]) * mesh.normals[i];
  }
  for (const glm::vec3& x : v)
    report.max_magnitude = std::max(report.max_magnitude, glm::length(x));
  if (report_out) *report_out = report;
  return v;
}

}  // namespace ibfvs
