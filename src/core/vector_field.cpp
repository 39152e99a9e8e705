#include "ibfvs/core/vector_field.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "ibfvs/core/curvature.h"
#include "ibfvs/core/error.h"
#include "ibfvs/core/lonlat_grid.h"

namespace ibfvs {

std::vector<std::string> split_colons(std::string_view text) {
  const std::string s(text);
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t colon; (colon = s.find(':', start)) != std::string::npos; start = colon + 1)
    parts.push_back(s.substr(start, colon - start));
  parts.push_back(s.substr(start));
  return parts;
}

std::vector<float> parse_numbers(std::string_view text, std::string_view what, std::size_t count,
                                 std::string_view expected) {
  const std::string s(text);
  std::vector<float> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = std::min(s.find(',', start), s.size());
    const std::string part = s.substr(start, comma - start);
    std::size_t used = 0;
    float v = 0.0f;
    try {
      v = std::stof(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || !std::isfinite(v))
      throw InputError(std::string(what) + ": '" + part + "' is not a finite number in '" + s +
                       "'");
    out.push_back(v);
    if (comma == s.size()) break;
    start = comma + 1;
  }
  if (count > 0 && out.size() != count)
    throw InputError(
        std::string(what) + ": expected " +
        (expected.empty() ? std::to_string(count) + " numbers" : std::string(expected)) +
        ", got '" + s + "'");
  return out;
}

int parse_int(std::string_view text, std::string_view what, int lo, int hi) {
  const std::string s(text);
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || v < lo || v > hi)
    throw InputError(std::string(what) + ": '" + s + "' must be a whole number in " +
                     std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

glm::vec3 parse_vec3(std::string_view text, std::string_view what) {
  const std::vector<float> v = parse_numbers(text, what, 3, "three numbers X,Y,Z");
  return {v[0], v[1], v[2]};
}

namespace {

// The optional parts of principal: and gradient: (a vector and one flag word).
void parse_options(const std::string& s, const std::vector<std::string>& parts, const char* flag,
                   bool& flag_value, glm::vec3& vector) {
  for (std::size_t i = 2; i < parts.size(); ++i) {
    if (parts[i] == flag) {
      flag_value = true;
    } else if (parts[i].find(',') != std::string::npos) {
      vector = parse_vec3(parts[i], "--field");
      if (glm::length(vector) == 0.0f)
        throw InputError("--field: the vector in '" + s + "' must not be zero");
    } else {
      throw InputError("--field: unknown part '" + parts[i] + "' in '" + s +
                       "' (expected X,Y,Z or " + flag + ")");
    }
  }
}

}  // namespace

FieldSpec FieldSpec::parse(std::string_view text) {
  FieldSpec spec;
  const std::string s(text);
  if (s == "file") {
    spec.kind = FieldKind::File;
    return spec;
  }
  const std::vector<std::string> parts = split_colons(s);
  if (parts[0] == "elements") {
    spec.kind = FieldKind::Elements;
    spec.value = parts.size() > 1 ? parse_vec3(parts[1], "--field elements") : glm::vec3(0.0f);
    if (parts.size() > 2) throw InputError("--field: expected elements[:X,Y,Z], got '" + s + "'");
    return spec;
  }
  if (parts[0] == "principal") {
    spec.kind = FieldKind::Principal;
    if (parts.size() < 2 || (parts[1] != "min" && parts[1] != "max"))
      throw InputError("--field: expected principal:min or principal:max, got '" + s + "'");
    spec.use_max = parts[1] == "max";
    spec.value = glm::vec3(0, 1, 0);
    std::vector<std::string> rest;
    for (const std::string& part : parts) {
      if (part.rfind("smooth=", 0) != 0) {
        rest.push_back(part);
        continue;
      }
      spec.smooth = parse_int(std::string_view(part).substr(7), "--field " + s, 0, 1000);
    }
    parse_options(s, rest, "rot90", spec.rotate90, spec.value);
    return spec;
  }
  if (parts[0] == "wind") {
    spec.kind = FieldKind::Wind;
    if (parts.size() != 2 && parts.size() != 4)
      throw InputError("--field: expected wind:FILE or wind:FILE:UVAR:VVAR, got '" + s + "'");
    spec.path = parts[1];
    if (parts.size() == 4) spec.east = parts[2], spec.north = parts[3];
    if (spec.path.empty() || spec.east.empty() || spec.north.empty())
      throw InputError("--field: empty file or variable name in '" + s + "'");
    return spec;
  }
  if (parts[0] == "gradient") {
    spec.kind = FieldKind::Gradient;
    if (parts.size() < 2 || (parts[1] != "down" && parts[1] != "up"))
      throw InputError("--field: expected gradient:down or gradient:up, got '" + s + "'");
    spec.downhill = parts[1] == "down";
    spec.value = glm::vec3(0, 1, 0);
    parse_options(s, parts, "normalize", spec.normalize, spec.value);
    return spec;
  }
  const std::size_t colon = s.find(':');
  const std::string name = s.substr(0, colon);
  if (colon == std::string::npos || (name != "uniform" && name != "rotate"))
    throw InputError("--field: unknown field '" + s +
                     "' (expected file, uniform:X,Y,Z, rotate:X,Y,Z, elements, "
                     "principal:min|max, gradient:down|up or wind:FILE)");
  spec.kind = name == "uniform" ? FieldKind::Uniform : FieldKind::Rotate;
  spec.value = parse_vec3(std::string_view(s).substr(colon + 1), "--field " + name);
  if (spec.kind == FieldKind::Rotate && glm::length(spec.value) == 0.0f)
    throw InputError("--field rotate: the axis must not be zero");
  return spec;
}

std::string FieldSpec::to_string() const {
  std::ostringstream out;
  const auto vec = [&] { out << value.x << "," << value.y << "," << value.z; };
  switch (kind) {
    case FieldKind::File:
      return "file";
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
