#include "ibfvs/core/fields/potential_flow.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {

FlowElement FlowElement::parse(std::string_view text) {
  const std::string s(text);
  const std::vector<float> v = parse_numbers(text);
  if (v.size() != 9 && v.size() != 10)
    throw InputError("expected AX,AY,AZ,BX,BY,BZ,ROTATIONAL,RADIAL,TANGENTIAL[,CORE], got '" + s +
                     "'");
  FlowElement e;
  e.a = {v[0], v[1], v[2]};
  e.b = {v[3], v[4], v[5]};
  e.rotational = v[6];
  e.radial = v[7];
  e.tangential = v[8];
  if (v.size() == 10) e.core = v[9];
  try {
    e.validate();
  } catch (const InputError& err) {
    throw InputError(std::string(err.what()) + " in '" + s + "'");
  }
  return e;
}

std::string FlowElement::to_string() const {
  std::string out = format_vec3(a) + "," + format_vec3(b) + "," + format_number(rotational) + "," +
                    format_number(radial) + "," + format_number(tangential);
  if (core != 0.0f) {
    out += ',';
    out += format_number(core);
  }
  return out;
}

void FlowElement::validate() const {
  if (!(glm::length(b - a) > 0.0f)) throw InputError("the flow element has zero length");
  if (!(core >= 0.0f) || !std::isfinite(core))
    throw InputError("the core radius must not be negative");
}

glm::vec3 FlowElement::velocity(const glm::vec3& r) const {
  const glm::vec3 axis = b - a;
  const float length = glm::length(axis);
  const glm::vec3 e = axis / length;
  const float t = std::clamp(glm::dot(r - a, e), 0.0f, length);
  const glm::vec3 d = r - (a + t * e);
  const float c = core > 0.0f ? core : 0.05f * length;
  const float rho2 = std::max(glm::dot(d, d), c * c);
  constexpr float k = 0.5f / std::numbers::pi_v<float>;
  return k * (rotational * glm::cross(e, d) / rho2 + radial * d / rho2 +
              tangential * e / std::sqrt(rho2));
}

glm::vec3 PotentialFlow::velocity(const glm::vec3& r) const {
  glm::vec3 v = uniform;
  for (const FlowElement& e : elements) v += e.velocity(r);
  return v;
}

}  // namespace ibfvs
