#include "ibfvs/core/support/text.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

std::vector<std::string> split_colons(std::string_view text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t colon; (colon = text.find(':', start)) != std::string_view::npos;
       start = colon + 1)
    parts.emplace_back(text.substr(start, colon - start));
  parts.emplace_back(text.substr(start));
  return parts;
}

double parse_number(std::string_view text) {
  const std::string s(text);
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v))
    throw InputError("'" + s + "' is not a finite number");
  return v;
}

std::vector<float> parse_numbers(std::string_view text, std::size_t count,
                                 std::string_view expected) {
  const std::string s(text);
  std::vector<float> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = std::min(s.find(',', start), s.size());
    const std::string part = s.substr(start, comma - start);
    double v = 0.0;
    try {
      v = parse_number(part);
    } catch (const InputError&) {
      throw InputError("'" + part + "' is not a finite number in '" + s + "'");
    }
    if (!std::isfinite(static_cast<float>(v)))
      throw InputError("'" + part + "' is out of range in '" + s + "'");
    out.push_back(static_cast<float>(v));
    if (comma == s.size()) break;
    start = comma + 1;
  }
  if (count > 0 && out.size() != count)
    throw InputError(
        "expected " +
        (expected.empty() ? std::to_string(count) + " numbers" : std::string(expected)) +
        ", got '" + s + "'");
  return out;
}

glm::vec3 parse_vec3(std::string_view text) {
  const std::vector<float> v = parse_numbers(text, 3, "three numbers X,Y,Z");
  return {v[0], v[1], v[2]};
}

long long parse_integer(std::string_view text, long long lo, long long hi) {
  long long v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end || v < lo || v > hi)
    throw InputError("'" + std::string(text) + "' must be a whole number in " + std::to_string(lo) +
                     ".." + std::to_string(hi));
  return v;
}

std::string format_number(double v) {
  char buf[64];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (static_cast<float>(std::strtod(buf, nullptr)) == static_cast<float>(v) ||
        std::strtod(buf, nullptr) == v)
      break;
  }
  return buf;
}

std::string format_vec3(const glm::vec3& v) {
  return format_number(v.x) + "," + format_number(v.y) + "," + format_number(v.z);
}

std::string excerpt(std::string_view text, std::size_t max) {
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < max; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    out += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
  }
  if (text.size() > max) out += "...";
  return out + "'";
}

bool glob_match(std::string_view pattern, std::string_view text) {
  // Iterative, with one backtrack point: linear in practice, never recursive.
  std::size_t p = 0, t = 0, star = std::string_view::npos, resume = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

}  // namespace ibfvs
