#pragma once
// Per-vertex vector fields (paper section 3.2: one velocity v_i per vertex):
// from the mesh file, uniform, a rigid rotation, potential-flow elements
// (section 4.1), principal directions (section 4.2) and the gradient of a
// height (section 4.1, figure 7); and the choice between projecting them on
// the tangent plane or using them in 3D (section 3.8).

#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/potential_flow.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/support/names.h"

namespace ibfvs {

/// The mesh's per-vertex vectors that `file[:NAME]` names: PLY's vx vy vz or
/// the only 3-component array for an empty name. Throws InputError that
/// lists the arrays there are, or says how many components NAME has.
const std::vector<glm::vec3>& file_vectors(const TriMesh& mesh, const std::string& name);

/// A one-line list of a mesh's arrays with their component counts, for
/// messages: "U (3), p (1), Tensor (9)"; "none" when it has none.
std::string describe_arrays(const TriMesh& mesh);

/// Where the vectors come from.
enum class FieldKind {
  File,       ///< the mesh file's vectors: PLY vx vy vz, or a named array
  Uniform,    ///< a constant 3D vector
  Rotate,     ///< v = w x (r - c), c the centre of the bounding box
  Elements,   ///< a uniform flow plus potential-flow elements
  Principal,  ///< unit principal directions, signed along a user vector
  Gradient,   ///< steepest descent or ascent of the height along a user axis
  Wind,       ///< eastward and northward components from a netCDF lon/lat grid
  Sample,     ///< a volume dataset's vector array sampled at the vertices
};

/// A parsed field spec (the scene key field):
///   file[:NAME]                            the mesh file's vector array NAME (VTK point
///                                          or cell data, OpenFOAM fields); without NAME
///                                          PLY's vx vy vz or the file's only 3-component
///                                          array
///   uniform:X,Y,Z                          a constant vector
///   rotate:X,Y,Z                           rotation about the axis through the box centre
///   elements[:X,Y,Z]                       uniform flow X,Y,Z (default 0) plus `elements`
///   principal:min|max[:X,Y,Z][:rot90][:smooth=K]
///                                          kappa_min or kappa_max directions, first
///                                          smoothed by K rounds of smooth_line_field
///                                          (default 0), each flipped to point along
///                                          X,Y,Z (default +Y), then optionally turned
///                                          90 degrees about n
///   gradient:down|up[:X,Y,Z][:normalize]   steepest descent or ascent of the height
///                                          along X,Y,Z (default +Y, up) on the surface
///   wind:FILE[:UVAR:VVAR]                  eastward and northward components (default
///                                          UWND, VWND) of a netCDF lon/lat grid at time
///                                          index `time`, on a sphere about the origin
///   sample:FILE:NAME[:OFFSET]              the vector array NAME of a volume dataset
///                                          (VTK, OpenFOAM) interpolated at the vertices
///                                          moved OFFSET (world units, default 0) along
///                                          their normals, or against them where that
///                                          point lies outside the volume
struct FieldSpec {
  FieldKind kind = FieldKind::Rotate;
  glm::vec3 value{0.0f, 1.0f, 0.0f};  ///< uniform vector, rotation axis, background flow,
                                      ///< alignment vector or height axis
  bool use_max = false;               ///< principal: kappa_max instead of kappa_min
  bool rotate90 = false;              ///< principal: turn 90 degrees about the normal
  int smooth = 0;                     ///< principal: rounds of line-field smoothing
  bool downhill = true;               ///< gradient: descent (true) or ascent
  bool normalize = false;             ///< gradient: unit vectors where the slope is not zero
  std::vector<FlowElement> elements;  ///< elements: the flow elements (the scene key element)
  std::string path;                   ///< wind: the netCDF file; sample: the volume dataset
  std::string array;                  ///< file, sample: the array's name (file: may be empty)
  float offset = 0.0f;                ///< sample: distance along the normal
  std::string east = "UWND";          ///< wind: eastward component variable
  std::string north = "VWND";         ///< wind: northward component variable
  std::size_t time = 0;               ///< wind: time index, from 0
  bool vector_given = false;          ///< principal, gradient: the text gave X,Y,Z (else +Y, or the
                                      ///< scene's height axis)

  /// Parses the textual form; throws InputError naming the text.
  static FieldSpec parse(std::string_view text);
  /// For messages: the text form plus the elements' count and the time index.
  [[nodiscard]] std::string to_string() const;
  /// The text form that parse() reads back (elements and time are kept apart).
  [[nodiscard]] std::string text() const;
};

/// How vectors with a normal component are used (section 3.8).
enum class TangentMode {
  Project,  ///< v - (v.n) n: the flow confined to the surface (default)
  Full3D,   ///< as given: "a wire mesh with little hairs aligned with the 3D flow"
};

template <>
struct EnumNames<TangentMode> {
  static constexpr EnumName<TangentMode> table[] = {
      {TangentMode::Project, "project", "v - (v.n) n, the flow on the surface"},
      {TangentMode::Full3D, "3d", "the vectors as given (3.8)"},
  };
};

/// What evaluate_field repaired.
struct FieldReport {
  std::size_t non_finite_zeroed = 0;  ///< vectors with NaN/inf set to zero
  float max_magnitude = 0.0f;         ///< after projection
  std::size_t outside_volume = 0;     ///< sample: vertices outside the volume (set to zero)
};

/// Evaluates the field at every vertex. Needs `mesh.normals` for projection.
/// Non-finite vectors are set to zero and counted in the report. Throws
/// InputError when `spec.kind == File` and the mesh carries no such vectors
/// (naming the arrays it has), or when every vector is non-finite.
std::vector<glm::vec3> evaluate_field(const TriMesh& mesh, const FieldSpec& spec, TangentMode mode,
                                      FieldReport* report = nullptr);

}  // namespace ibfvs
