// The dates of a CF time axis. The Gregorian calendar is std::chrono's; the
// others count days the same way (a day number, 0 at 1970-01-01 in the
// Gregorian calendar), each with its own years.
#include "ibfvs/core/fields/cf_time.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <regex>
#include <utility>

#include "ibfvs/core/support/text.h"

namespace ibfvs {
namespace {

constexpr long long kYearLimit = 32767;  // std::chrono::year's range
constexpr long long kSecondsPerDay = 86400;

struct Date {
  long long year = 0;
  int month = 1, day = 1;
};

enum class Calendar { Standard, Gregorian, Julian, NoLeap, AllLeap, Day360 };

std::optional<Calendar> calendar_named(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (name.empty() || name == "standard" || name == "gregorian") return Calendar::Standard;
  if (name == "proleptic_gregorian") return Calendar::Gregorian;
  if (name == "julian") return Calendar::Julian;
  if (name == "noleap" || name == "365_day") return Calendar::NoLeap;
  if (name == "all_leap" || name == "366_day") return Calendar::AllLeap;
  if (name == "360_day") return Calendar::Day360;
  return std::nullopt;
}

long long floor_div(long long a, long long b) {
  return a / b - ((a % b != 0) && ((a < 0) != (b < 0)));
}

// ---- Gregorian (std::chrono)
long long gregorian_days(const Date& d) {
  using namespace std::chrono;
  return sys_days{year{static_cast<int>(d.year)} / month{static_cast<unsigned>(d.month)} /
                  day{static_cast<unsigned>(d.day)}}
      .time_since_epoch()
      .count();
}
Date gregorian_date(long long n) {
  using namespace std::chrono;
  const year_month_day ymd{sys_days{days{n}}};
  return {static_cast<int>(ymd.year()), static_cast<int>(static_cast<unsigned>(ymd.month())),
          static_cast<int>(static_cast<unsigned>(ymd.day()))};
}
bool gregorian_valid(const Date& d) {
  using namespace std::chrono;
  return year_month_day{year{static_cast<int>(d.year)}, month{static_cast<unsigned>(d.month)},
                        day{static_cast<unsigned>(d.day)}}
      .ok();
}

// ---- Julian: a leap year every fourth, counted in four-year cycles of years
// that begin in March (the leap day ends a cycle), aligned so that
// 1582-10-05 Julian is 1582-10-15 Gregorian.
long long julian_count(const Date& d) {
  const long long y = d.year - (d.month <= 2);
  const long long cycle = floor_div(y, 4), year_of_cycle = y - cycle * 4;
  const long long day_of_year =
      (153 * (d.month > 2 ? d.month - 3 : d.month + 9) + 2) / 5 + d.day - 1;
  return cycle * 1461 + year_of_cycle * 365 + day_of_year;
}
long long julian_shift() {
  static const long long shift = gregorian_days({1582, 10, 15}) - julian_count({1582, 10, 5});
  return shift;
}
long long julian_days(const Date& d) {
  return julian_count(d) + julian_shift();
}
Date julian_date(long long n) {
  const long long z = n - julian_shift();
  const long long cycle = floor_div(z, 1461), in_cycle = z - cycle * 1461;
  const long long year_of_cycle = std::min<long long>(in_cycle / 365, 3);
  const long long day_of_year = in_cycle - year_of_cycle * 365;
  const long long mp = (5 * day_of_year + 2) / 153;
  Date d;
  d.day = static_cast<int>(day_of_year - (153 * mp + 2) / 5 + 1);
  d.month = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  d.year = cycle * 4 + year_of_cycle + (d.month <= 2);
  return d;
}
bool julian_valid(const Date& d) {
  static constexpr std::array<int, 12> length{31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (d.month < 1 || d.month > 12 || d.day < 1 || d.day > length[d.month - 1]) return false;
  return d.month != 2 || d.day < 29 || floor_div(d.year, 4) * 4 == d.year;
}

// ---- Years of a fixed length: 365 days, 366 days, or twelve months of 30.
std::array<int, 12> month_lengths(Calendar c) {
  if (c == Calendar::Day360) return {30, 30, 30, 30, 30, 30, 30, 30, 30, 30, 30, 30};
  return {31, c == Calendar::AllLeap ? 29 : 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
}
long long fixed_days(const Date& d, Calendar c) {
  const std::array<int, 12> lengths = month_lengths(c);
  long long n = d.year * (c == Calendar::Day360 ? 360 : c == Calendar::AllLeap ? 366 : 365);
  for (int m = 1; m < d.month; ++m) n += lengths[m - 1];
  return n + d.day - 1;
}
Date fixed_date(long long n, Calendar c) {
  const std::array<int, 12> lengths = month_lengths(c);
  const long long per_year = c == Calendar::Day360 ? 360 : c == Calendar::AllLeap ? 366 : 365;
  Date d;
  d.year = floor_div(n, per_year);
  long long rest = n - d.year * per_year;
  while (rest >= lengths[d.month - 1]) rest -= lengths[d.month++ - 1];
  d.day = static_cast<int>(rest + 1);
  return d;
}
bool fixed_valid(const Date& d, Calendar c) {
  return d.month >= 1 && d.month <= 12 && d.day >= 1 && d.day <= month_lengths(c)[d.month - 1];
}

bool before_gregorian(const Date& d) {
  return d.year < 1582 || (d.year == 1582 && (d.month < 10 || (d.month == 10 && d.day < 15)));
}

// A date's day number in a calendar; nothing where it is not a date there.
std::optional<long long> day_number(const Date& d, Calendar c) {
  switch (c) {
    case Calendar::Standard:
      if (!before_gregorian(d))
        return gregorian_valid(d) ? std::optional(gregorian_days(d)) : std::nullopt;
      // 1582-10-05 to 1582-10-14 were never days: Julian until 10-04.
      if (d.year == 1582 && d.month == 10 && d.day > 4) return std::nullopt;
      return julian_valid(d) ? std::optional(julian_days(d)) : std::nullopt;
    case Calendar::Gregorian:
      return gregorian_valid(d) ? std::optional(gregorian_days(d)) : std::nullopt;
    case Calendar::Julian:
      return julian_valid(d) ? std::optional(julian_days(d)) : std::nullopt;
    default:
      return fixed_valid(d, c) ? std::optional(fixed_days(d, c)) : std::nullopt;
  }
}

Date date_of(long long n, Calendar c) {
  switch (c) {
    case Calendar::Standard:
      return n >= gregorian_days({1582, 10, 15}) ? gregorian_date(n) : julian_date(n);
    case Calendar::Gregorian:
      return gregorian_date(n);
    case Calendar::Julian:
      return julian_date(n);
    default:
      return fixed_date(n, c);
  }
}

std::optional<double> unit_seconds(const std::string& unit) {
  static const std::array<std::pair<const char*, double>, 21> units{{
      {"s", 1},
      {"sec", 1},
      {"secs", 1},
      {"second", 1},
      {"seconds", 1},
      {"min", 60},
      {"mins", 60},
      {"minute", 60},
      {"minutes", 60},
      {"h", 3600},
      {"hr", 3600},
      {"hrs", 3600},
      {"hour", 3600},
      {"hours", 3600},
      {"d", 86400},
      {"day", 86400},
      {"days", 86400},
      {"ms", 1e-3},
      {"msec", 1e-3},
      {"millisecond", 1e-3},
      {"milliseconds", 1e-3},
  }};
  for (const auto& [name, seconds] : units)
    if (unit == name) return seconds;
  return std::nullopt;
}

std::string two(long long v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%02lld", v);
  return buf;
}

}  // namespace

std::optional<std::string> cf_date(double value, std::string_view units,
                                   std::string_view calendar) {
  const std::optional<Calendar> c = calendar_named(std::string(calendar));
  // A file's text: std::regex recurses over its length, so no more than a
  // CF unit ever needs.
  if (!c || !std::isfinite(value) || units.size() > 128) return std::nullopt;
  // UNIT since Y-M-D [h[:m[:s[.f]]]] [ZONE]: dates in the origin's zone (as
  // cftime and xarray give them)
  static const std::regex form(
      R"(\s*([a-z]+)\s+since\s+([+-]?\d{1,5})-(\d{1,2})-(\d{1,2})(?:(?:\s+|t)(\d{1,2})(?::(\d{1,2})(?::(\d{1,2}(?:\.\d*)?))?)?)?\s*(z|utc|gmt|[+-]\d{1,2}(?::?\d{2})?)?\s*)",
      std::regex::icase);
  const std::string text(units);
  std::smatch m;
  if (!std::regex_match(text, m, form)) return std::nullopt;
  std::string unit = m[1];
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  const std::optional<double> seconds_per_unit = unit_seconds(unit);
  if (!seconds_per_unit) return std::nullopt;  // months, years: no fixed length in CF
  const Date origin{std::stoll(m[2]), std::stoi(m[3]), std::stoi(m[4])};
  if (std::llabs(origin.year) > kYearLimit) return std::nullopt;
  const int hour = m[5].matched ? std::stoi(m[5]) : 0, minute = m[6].matched ? std::stoi(m[6]) : 0;
  const double second = m[7].matched ? std::stod(m[7]) : 0.0;
  if (hour > 23 || minute > 59 || second >= 61.0) return std::nullopt;
  const std::optional<long long> origin_day = day_number(origin, *c);
  if (!origin_day) return std::nullopt;
  const double total = static_cast<double>(*origin_day) * kSecondsPerDay + hour * 3600.0 +
                       minute * 60.0 + second + value * *seconds_per_unit;
  // Beyond the years the calendars count here (a sentinel such as 1e36).
  if (!(std::abs(total) < kYearLimit * 366.0 * kSecondsPerDay)) return std::nullopt;
  const long long t = std::llround(total);
  const long long day = floor_div(t, kSecondsPerDay), second_of_day = t - day * kSecondsPerDay;
  const Date d = date_of(day, *c);
  if (std::llabs(d.year) > kYearLimit) return std::nullopt;
  char year[16];
  std::snprintf(year, sizeof year, d.year < 0 ? "-%04lld" : "%04lld", std::llabs(d.year));
  std::string out = std::string(year) + "-" + two(d.month) + "-" + two(d.day);
  if (second_of_day != 0) {
    out += " " + two(second_of_day / 3600) + ":" + two(second_of_day / 60 % 60);
    if (second_of_day % 60 != 0) out += ":" + two(second_of_day % 60);
  }
  return out;
}

std::vector<std::string> time_labels(const TimeAxis& axis, std::size_t first, std::size_t last) {
  std::vector<std::string> out;
  if (first > last || last >= axis.values.size()) return out;
  for (std::size_t k = first; k <= last; ++k) {
    const double v = axis.values[k];
    if (std::optional<std::string> date = cf_date(v, axis.units, axis.calendar)) {
      out.push_back(std::move(*date));
      continue;
    }
    std::string label = format_number(v);
    if (!axis.units.empty()) {  // printable, and short: a file's text
      const std::string units = excerpt(axis.units, 60);
      label.append(" ").append(units, 1, units.size() - 2);  // without excerpt's quotes
    }
    out.push_back(std::move(label));
  }
  return out;
}

}  // namespace ibfvs
