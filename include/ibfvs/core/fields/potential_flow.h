#pragma once
// Potential-flow elements (paper section 4.1, after van Wijk's "Flow
// visualization with surface particles", 1993): a uniform background flow plus
// line segments that swirl, push or pull, and drag the flow along themselves.
//
// For a point r, let q be the nearest point of the segment [a, b], d = r - q,
// e = (b - a)/|b - a|, and rho^2 = max(|d|^2, c^2) with c the core radius. Then
//   rotational  v = S_rot / (2 pi) * (e x d) / rho^2   (a line vortex: circles about the line)
//   radial      v = S_rad / (2 pi) * d / rho^2         (a line source; S_rad < 0 attracts)
//   tangential  v = S_tan / (2 pi) * e / rho           (flow along the line, fading with distance)
// Away from the ends these are the classic 2D point vortex and source about
// the line's axis. The only singularity, on the segment itself, is clamped by
// the core radius c: inside it the rotational and radial speeds grow linearly
// to their value at c, and the tangential speed stays at its value at c.

#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace ibfvs {

struct FlowElement {
  glm::vec3 a{0.0f};              ///< first end of the segment
  glm::vec3 b{0.0f, 1.0f, 0.0f};  ///< second end
  float rotational = 0.0f;        ///< swirl about the line (right-handed about a -> b)
  float radial = 0.0f;            ///< > 0 repels, < 0 attracts
  float tangential = 0.0f;        ///< along a -> b
  float core = 0.0f;              ///< core radius; 0: 5% of the segment length

  /// Parses "AX,AY,AZ,BX,BY,BZ,ROT,RAD,TAN[,CORE]". Throws InputError for a
  /// wrong count, a non-finite number or a zero-length segment.
  static FlowElement parse(std::string_view text);
  /// The text parse() reads back.
  [[nodiscard]] std::string to_string() const;
  /// Throws InputError for a zero-length segment or a negative core.
  void validate() const;
  /// The velocity this element induces at r.
  [[nodiscard]] glm::vec3 velocity(const glm::vec3& r) const;
};

/// A uniform flow plus elements; velocities add (the flow is linear in them).
struct PotentialFlow {
  glm::vec3 uniform{0.0f};
  std::vector<FlowElement> elements;
  [[nodiscard]] glm::vec3 velocity(const glm::vec3& r) const;
};

}  // namespace ibfvs
