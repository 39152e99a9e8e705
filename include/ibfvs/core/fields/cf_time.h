#pragma once
// The dates of a time axis as the CF conventions (cfconventions.org, 4.4
// "Time Coordinate") state them: values in "UNIT since DATE [TIME [ZONE]]"
// in one of the CF calendars. What names a step of a netCDF series in the
// command's summary, the viewer's panel and Python (`step_labels`).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ibfvs {

/// A time coordinate as a file gives it: its values, its `units` and
/// `calendar` attributes (empty where absent). Empty values: no axis.
struct TimeAxis {
  std::vector<double> values;
  std::string units;
  std::string calendar;
};

/// The date of `value` on a CF time axis: "YYYY-MM-DD", with " hh:mm" (and
/// ":ss") where the time of day is not midnight, to the nearest second, in
/// the zone the origin is written in (a zone offset is read and not
/// applied, as cftime and xarray show dates).
/// UNIT is seconds, minutes, hours or days (months and years are not fixed
/// lengths in CF, so they give none); the calendars are standard (also
/// gregorian, and the default: Julian before 1582-10-15, Gregorian from
/// it), proleptic_gregorian, julian, noleap (365_day), all_leap (366_day)
/// and 360_day. Years are astronomical (year 0 is 1 BC). Nothing where the
/// units are not a time since a date, the calendar is another, the value
/// is not finite or the date is beyond year +-1,000,000.
[[nodiscard]] std::optional<std::string> cf_date(double value, std::string_view units,
                                                 std::string_view calendar = {});

/// A label for each of the axis's values `first` to `last` (inclusive):
/// its date (cf_date), else the value and its units as the file states
/// them ("17598 hour since ..."). Empty where the axis is, or the range is
/// outside it.
[[nodiscard]] std::vector<std::string> time_labels(const TimeAxis& axis, std::size_t first,
                                                   std::size_t last);

}  // namespace ibfvs
