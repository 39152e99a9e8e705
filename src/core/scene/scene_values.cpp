// The scene's value types read from and written as text: GridScalar,
// Displacement, ScalarRange, TimeRange (scene.h).
#include <cmath>
#include <cstdint>
#include <sstream>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {

GridScalar GridScalar::parse(std::string_view text) {
  const std::string s(text);
  const std::size_t eq = s.find('='), colon = s.rfind(':');
  if (eq == std::string::npos || colon == std::string::npos || colon < eq || eq == 0 ||
      colon == eq + 1 || colon + 1 == s.size())
    throw InputError("expected NAME=FILE:VAR, got '" + s + "'");
  return {s.substr(0, eq), s.substr(eq + 1, colon - eq - 1), s.substr(colon + 1)};
}

std::string GridScalar::to_string() const {
  return name + "=" + path + ":" + variable;
}

Displacement Displacement::parse(std::string_view text) {
  const std::string s(text);
  const std::size_t colon = s.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw InputError("expected NAME:FACTOR, got '" + s + "'");
  try {
    return {s.substr(0, colon), static_cast<float>(parse_number(s.substr(colon + 1)))};
  } catch (const InputError&) {
    throw InputError("expected NAME:FACTOR, got '" + s + "'");
  }
}

std::string Displacement::to_string() const {
  return scalar + ":" + format_number(factor);
}

ScalarRange ScalarRange::parse(std::string_view text) {
  const std::string s(text);
  ScalarRange r;
  if (!s.empty() && s[0] == 'p') {
    // "pA,pB": the A-th and B-th percentiles.
    const std::size_t comma = s.find(",p");
    std::vector<float> q;
    if (comma != std::string::npos) {
      try {
        q = parse_numbers(s.substr(1, comma - 1) + "," + s.substr(comma + 2), 2);
      } catch (const InputError&) {
      }
    }
    if (q.size() != 2 || !(q[0] >= 0.0f && q[1] <= 100.0f && q[0] < q[1]))
      throw InputError("expected percentiles pA,pB with 0 <= A < B <= 100, got '" + s + "'");
    return {true, q[0], q[1]};
  }
  const std::vector<float> v = parse_numbers(s, 2, "LO,HI");
  if (!(v[1] > v[0])) throw InputError("expected LO,HI with LO < HI, got '" + s + "'");
  r.lo = v[0];
  r.hi = v[1];
  return r;
}

std::string ScalarRange::to_string() const {
  return percentile ? "p" + format_number(lo) + ",p" + format_number(hi)
                    : format_number(lo) + "," + format_number(hi);
}

TimeRange TimeRange::parse(std::string_view text) {
  const std::string s(text);
  const std::size_t colon = s.find(':');
  const auto index = [&](const std::string& part) {
    try {
      return static_cast<std::size_t>(parse_integer(part, 0, 1000000000));
    } catch (const InputError&) {
      throw InputError("expected an index from 0 or a range A:B, got '" + s + "'");
    }
  };
  TimeRange t;
  t.first = index(s.substr(0, colon));
  t.last = colon == std::string::npos ? t.first : index(s.substr(colon + 1));
  if (t.last < t.first) throw InputError("the range " + s + " runs backwards");
  return t;
}

std::string TimeRange::to_string() const {
  return last > first ? std::to_string(first) + ":" + std::to_string(last) : std::to_string(first);
}

}  // namespace ibfvs
