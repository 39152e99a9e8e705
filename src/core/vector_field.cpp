#include "ibfvs/core/vector_field.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "ibfvs/core/error.h"

namespace ibfvs {

glm::vec3 parse_vec3(std::string_view text, std::string_view what) {
  const std::string s(text);
  float v[3];
  std::size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = s.find(',', start);
    if ((k < 2) != (comma != std::string::npos))
      throw InputError(std::string(what) + ": expected three numbers X,Y,Z, got '" + s + "'");
    const std::string part =
        s.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    std::size_t used = 0;
    try {
      v[k] = std::stof(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || !std::isfinite(v[k]))
      throw InputError(std::string(what) + ": '" + part + "' is not a finite number in '" + s +
                       "'");
    start = comma + 1;
  }
  return {v[0], v[1], v[2]};
}

FieldSpec FieldSpec::parse(std::string_view text) {
  FieldSpec spec;
  const std::string s(text);
  if (s == "file") {
    spec.kind = FieldKind::File;
    return spec;
  }
  const std::size_t colon = s.find(':');
  const std::string name = s.substr(0, colon);
  if (colon == std::string::npos || (name != "uniform" && name != "rotate"))
    throw InputError("--field: unknown field '" + s +
                     "' (expected file, uniform:X,Y,Z or rotate:X,Y,Z)");
  spec.kind = name == "uniform" ? FieldKind::Uniform : FieldKind::Rotate;
  spec.value = parse_vec3(std::string_view(s).substr(colon + 1), "--field " + name);
  if (spec.kind == FieldKind::Rotate && glm::length(spec.value) == 0.0f)
    throw InputError("--field rotate: the axis must not be zero");
  return spec;
}

std::string FieldSpec::to_string() const {
  if (kind == FieldKind::File) return "file";
  std::ostringstream out;
  out << (kind == FieldKind::Uniform ? "uniform:" : "rotate:") << value.x << "," << value.y << ","
      << value.z;
  return out.str();
}

TangentMode parse_tangent_mode(std::string_view text) {
  if (text == "project") return TangentMode::Project;
  if (text == "3d") return TangentMode::Full3D;
  throw InputError("--tangent: expected project or 3d, got '" + std::string(text) + "'");
}

std::vector<glm::vec3> evaluate_field(const TriMesh& mesh, const FieldSpec& spec, TangentMode mode,
                                      FieldReport* report_out) {
  FieldReport report;
  const std::size_t n = mesh.vertex_count();
  std::vector<glm::vec3> v(n);
  switch (spec.kind) {
    case FieldKind::File:
      if (mesh.vectors.size() != n)
        throw InputError(
            "--field file: the mesh has no per-vertex vectors (PLY vertex properties vx vy vz)");
      v = mesh.vectors;
      break;
    case FieldKind::Uniform:
      std::fill(v.begin(), v.end(), spec.value);
      break;
    case FieldKind::Rotate: {
      const glm::vec3 c = mesh_bounds(mesh).centre();
      for (std::size_t i = 0; i < n; ++i) v[i] = glm::cross(spec.value, mesh.positions[i] - c);
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
