#pragma once
// The topology between two steps of a series, as the overlay draws it
// (issue 73): a feature that persists from one step to the next (the same id:
// carry_ids, topology.h) moves from where it was to where it will be, as the
// texture's field and surface do between the steps; a feature that does not
// persist (a bifurcation: a saddle and a node born or cancelled together, a
// line that forms or breaks) is drawn until halfway through the step, or from
// halfway on, so the picture never shows both the old and the new state.
// A point whose kind changes (a node that becomes a focus) moves on and
// takes its new kind halfway. A line is resampled at the same fractions of
// its length at both steps (a closed one from the points nearest each
// other). A point moves along the surface, not through it: along the
// parabola through its two places that bulges at halfway along the mean of
// their normals by the sagitta of an arc with those normals (exact to
// second order in the distance moved: (b - a) . (n_b - n_a) / 8).
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/topology.h"

namespace ibfvs {

/// When in a step (the fraction `mix`, 0 to 1) a feature is drawn.
enum class MorphSpan : int {
  Whole = 0,       ///< persists: always
  FirstHalf = 1,   ///< only at the first step: while mix < 0.5
  SecondHalf = 2,  ///< only at the second step: from mix 0.5 on
};

/// One feature between the steps: a point (one position) or a line
/// (`from` and `to` the same count of positions).
struct FeatureMorph {
  int kind = 0;  ///< CriticalKind or LineKind
  int id = -1;
  bool point = false;
  bool closed = false;
  MorphSpan span = MorphSpan::Whole;
  std::vector<glm::vec3> from, to;
  std::vector<glm::vec3> bulge;  ///< each point's offset from the chord halfway
  /// Point i at `mix`: from + mix (to - from) + 4 mix (1 - mix) bulge.
  [[nodiscard]] glm::vec3 at(std::size_t i, float mix) const;
};

/// The features between two steps, and the counts the legend shows at each.
struct TopologyMorph {
  std::vector<FeatureMorph> features;
  FlowTopology first, second;  ///< the two steps (for their counts)
};

/// The features of `from` and `to` paired by id (`to`'s carried from `from`
/// with carry_ids).
TopologyMorph morph_steps(const FlowTopology& from, const FlowTopology& to);

/// One step held still: every feature Whole, `from` equal to `to`.
TopologyMorph hold(const FlowTopology& topology);

/// What is drawn at `mix`: the features shown then, where they are then
/// (lines with positions alone; points with their kind and position). The
/// CPU reference of the overlay's morph.
FlowTopology topology_at(const TopologyMorph& morph, float mix);

/// Whether a feature of `span` is drawn at `mix`.
bool shown_at(MorphSpan span, float mix);

}  // namespace ibfvs
