// The dates of CF time axes: each calendar against dates cftime (the CF
// reference library in Python) gives for the same values.
#include "ibfvs/core/fields/cf_time.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace ibfvs {
namespace {

TEST(CfTime, TheNavyWindsAxisGivesItsDates) {
  // monthly_navy_winds.cdf's TIME: its first and last values.
  const char* units = "hour since 1980-01-14 14:00:00";
  EXPECT_EQ(cf_date(17598, units), "1982-01-16 20:00");
  EXPECT_EQ(cf_date(113293.5, units), "1992-12-17 03:30");
  EXPECT_EQ(cf_date(0, units), "1980-01-14 14:00");
  EXPECT_EQ(cf_date(-1.0 / 3600.0, "hours since 1970-01-01"), "1969-12-31 23:59:59");
}

TEST(CfTime, EachCalendarCountsItsOwnDays) {
  EXPECT_EQ(cf_date(59, "days since 2000-01-01", "noleap"), "2000-03-01");
  EXPECT_EQ(cf_date(59, "days since 2000-01-01", "365_day"), "2000-03-01");
  EXPECT_EQ(cf_date(59, "days since 2000-01-01", "all_leap"), "2000-02-29");
  EXPECT_EQ(cf_date(59, "days since 2000-01-01", "360_day"), "2000-02-30");
  EXPECT_EQ(cf_date(59, "days since 2001-01-01", "standard"), "2001-03-01");
  EXPECT_EQ(cf_date(146100, "days since 1000-01-01", "julian"), "1400-01-01");
  EXPECT_EQ(cf_date(146100, "days since 1000-01-01", "proleptic_gregorian"), "1400-01-04");
  // The standard calendar is Julian until 1582-10-04, Gregorian from the
  // next day, 1582-10-15; a date between was never a day.
  EXPECT_EQ(cf_date(1, "days since 1582-10-04", "standard"), "1582-10-15");
  EXPECT_EQ(cf_date(-1, "days since 1582-10-15", "gregorian"), "1582-10-04");
  EXPECT_EQ(cf_date(1, "days since 1582-10-04", "proleptic_gregorian"), "1582-10-05");
  EXPECT_EQ(cf_date(0, "days since 1582-10-10"), std::nullopt);
  // A climatology's year 0 (coads_climatology.cdf): Julian, a leap year.
  EXPECT_EQ(cf_date(366, "hour since 0000-01-01 00:00:00"), "0000-01-16 06:00");
  EXPECT_EQ(cf_date(59, "days since 0000-01-01"), "0000-02-29");
  EXPECT_EQ(cf_date(-1, "days since 0000-01-01", "proleptic_gregorian"), "-0001-12-31");
}

TEST(CfTime, TheUnitsAreReadAsCfWritesThem) {
  EXPECT_EQ(cf_date(90, "minutes since 2010-6-1"), "2010-06-01 01:30");
  EXPECT_EQ(cf_date(1.5, "Days Since 1900-02-28 12:00 -6:00"), "1900-03-02");
  EXPECT_EQ(cf_date(30, "seconds since 1992-10-8T15:15:42.25Z"), "1992-10-08 15:16:12");
  EXPECT_EQ(cf_date(2, "d since 2020-02-28 UTC"), "2020-03-01");
  EXPECT_EQ(cf_date(1, "hours since 2020-01-01 5"), "2020-01-01 06:00");
}

TEST(CfTime, WhatIsNoDateGivesNone) {
  EXPECT_EQ(cf_date(1, "months since 2000-01-01"), std::nullopt);  // no fixed length
  EXPECT_EQ(cf_date(1, "years since 2000-01-01"), std::nullopt);
  EXPECT_EQ(cf_date(1, "m/s"), std::nullopt);
  EXPECT_EQ(cf_date(1, ""), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 2000-13-01"), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 2001-02-29"), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 2000-01-01 25:00"), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 2000-01-01 junk"), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 2000-01-01", "lunar"), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 2000-01-01", "none"), std::nullopt);
  EXPECT_EQ(cf_date(std::numeric_limits<double>::quiet_NaN(), "days since 2000-01-01"),
            std::nullopt);
  EXPECT_EQ(cf_date(1e36, "days since 2000-01-01"), std::nullopt);  // a fill value
  EXPECT_EQ(cf_date(-1e36, "seconds since 2000-01-01"), std::nullopt);
  EXPECT_EQ(cf_date(1, "days since 99999-01-01"), std::nullopt);
}

TEST(CfTime, LabelsAreDatesElseTheValueAndItsUnits) {
  TimeAxis axis{{17598, 18328.5, 19059}, "hour since 1980-01-14 14:00:00", ""};
  EXPECT_EQ(time_labels(axis, 1, 2),
            (std::vector<std::string>{"1982-02-16 06:30", "1982-03-18 17:00"}));
  EXPECT_TRUE(time_labels(axis, 2, 3).empty());
  EXPECT_TRUE(time_labels({}, 0, 0).empty());
  axis.units = "months since 2000-01";
  EXPECT_EQ(time_labels(axis, 1, 1), std::vector<std::string>{"18328.5 months since 2000-01"});
  axis.units = "";
  EXPECT_EQ(time_labels(axis, 0, 0), std::vector<std::string>{"17598"});
  // A file's text: printable and short in a label, and no date past 128 bytes.
  axis.units = "days\nsince " + std::string(100, 'x');
  const std::string label = time_labels(axis, 0, 0).front();
  EXPECT_EQ(label, "17598 days?since " + std::string(49, 'x') + "...");
  EXPECT_EQ(cf_date(1, "days since 2000-01-01" + std::string(200, ' ')), std::nullopt);
}

}  // namespace
}  // namespace ibfvs
