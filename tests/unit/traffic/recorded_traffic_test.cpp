#include "skyfuse/traffic/recorded_traffic.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse {
namespace {

constexpr double kT0 = 1700000000.0;  // 2023-11-14, a Unix time of OpenSky's magnitude
constexpr std::string_view kOpenSkyHeader =
    "time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,"
    "baroaltitude,geoaltitude,lastposupdate,lastcontact";

/// One line of an OpenSky state-vector file; empty optionals are written as empty fields.
struct StateRow {
  double time = kT0;
  std::string icao24 = "3c6444";
  std::optional<double> lat, lon, velocity, heading, vertrate;
  bool onground = false;
  std::optional<double> baroaltitude, geoaltitude, lastposupdate;
  std::string callsign = "DLH4AB  ";  // as OpenSky writes it: padded to 8
};

std::string field(const std::optional<double>& value) {
  return value ? fmt::format("{}", *value) : std::string();
}

std::string csv_line(const StateRow& row) {
  return fmt::format("{},{},{},{},{},{},{},{},{},false,false,1000,{},{},{},{}", row.time,
                     row.icao24, field(row.lat), field(row.lon), field(row.velocity),
                     field(row.heading), field(row.vertrate), row.callsign,
                     row.onground ? "true" : "false", field(row.baroaltitude),
                     field(row.geoaltitude), field(row.lastposupdate), row.time);
}

/// Writes `lines` under the test's own name in GoogleTest's temporary directory.
std::filesystem::path write_file(const std::vector<std::string>& lines) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path path =
      std::filesystem::path(::testing::TempDir()) /
      fmt::format("skyfuse_{}_{}.csv", test->test_suite_name(), test->name());
  std::ofstream out(path, std::ios::trunc);
  for (const std::string& line : lines) out << line << '\n';
  return path;
}

std::filesystem::path write_states(const std::vector<StateRow>& rows) {
  std::vector<std::string> lines{std::string(kOpenSkyHeader)};
  for (const StateRow& row : rows) lines.push_back(csv_line(row));
  return write_file(lines);
}

/// A row for an aircraft at `enu` in `anchor`'s frame with velocity `velocity_enu` there,
/// written as OpenSky would: latitude, longitude and height, and speed, heading and vertical
/// rate in the aircraft's own east-north-up axes.
StateRow row_at(const GeoAnchor& anchor, double time, const Vector3& enu,
                const Vector3& velocity_enu) {
  const Vector3 geodetic = from_local_enu(anchor, enu);
  const Vector3 local =
      ecef_to_enu_rotation(geodetic.x(), geodetic.y()) *
      ecef_to_enu_rotation(anchor.latitude_deg, anchor.longitude_deg).transpose() * velocity_enu;
  StateRow row;
  row.time = time;
  row.lat = geodetic.x();
  row.lon = geodetic.y();
  row.geoaltitude = geodetic.z();
  row.baroaltitude = geodetic.z() + 40.0;  // a pressure altitude, off by tens of metres
  row.velocity = std::hypot(local.x(), local.y());
  row.heading =
      std::fmod(std::atan2(local.x(), local.y()) * 180.0 / std::numbers::pi + 360.0, 360.0);
  row.vertrate = local.z();
  row.lastposupdate = time;
  return row;
}

const Vector3 kStart(-5000.0, -3000.0, 3000.0);
const Vector3 kVelocity(150.0, 80.0, 0.0);

/// Straight flight at kVelocity through kStart, sampled every 10 s for 60 s from kT0.
std::vector<StateRow> straight_flight(const GeoAnchor& anchor) {
  std::vector<StateRow> rows;
  for (int i = 0; i <= 6; ++i) {
    const double t = 10.0 * i;
    rows.push_back(row_at(anchor, kT0 + t, kStart + t * kVelocity, kVelocity));
  }
  return rows;
}

RecordedTrafficOptions steps_of(double time_step_s, int steps) {
  RecordedTrafficOptions options;
  options.time_step_s = time_step_s;
  options.steps = steps;
  return options;
}

void expect_near(const Vector3& actual, const Vector3& expected, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(actual(i), expected(i), tolerance) << "component " << i;
  }
}

TEST(RecordedTraffic, StraightFlightIsExactAtTheSamplesAndWithinCentimetresBetween) {
  const GeoAnchor anchor;
  const RecordedTraffic traffic =
      read_opensky_states(write_states(straight_flight(anchor)), anchor, steps_of(0.1, 600));
  EXPECT_EQ(traffic.rows, 7U);
  ASSERT_EQ(traffic.targets.size(), 1U);
  const TargetTruth& target = traffic.targets[0];
  EXPECT_EQ(target.label, "3c6444");
  EXPECT_EQ(target.first_step, 0);
  ASSERT_EQ(target.states.size(), 601U);
  for (int step = 0; step <= 600; ++step) {
    const double t = 0.1 * step;
    const auto& state = target.at(step);
    const double tolerance = step % 100 == 0 ? 1e-6 : 0.01;
    expect_near(state.head<3>(), kStart + t * kVelocity, tolerance);
    expect_near(state.segment<3>(3), kVelocity, 1e-6);
    expect_near(state.tail<3>(), Vector3::Zero(), 1e-6);
  }
}

TEST(RecordedTraffic, StepsBetweenTheSamplesFollowTheFlight) {
  const GeoAnchor anchor;
  RecordedTrafficOptions options = steps_of(0.3, 300);
  options.start_time_s = kT0 + 0.05;
  const RecordedTraffic traffic =
      read_opensky_states(write_states(straight_flight(anchor)), anchor, options);
  ASSERT_EQ(traffic.targets.size(), 1U);
  const TargetTruth& target = traffic.targets[0];
  // The last sample, at 60 s, is step (60 - 0.05) / 0.3 = 199.8: step 199 is the last.
  EXPECT_EQ(target.first_step, 0);
  EXPECT_EQ(target.states.size(), 200U);
  for (int step = 0; step < 200; ++step) {
    expect_near(target.at(step).head<3>(), kStart + (0.05 + 0.3 * step) * kVelocity, 0.01);
  }
}

TEST(RecordedTraffic, HeadingNinetyFliesEast) {
  const GeoAnchor anchor;
  // Over the anchor itself, where the aircraft's axes are the anchor's.
  std::vector<StateRow> rows(2);
  for (int i = 0; i < 2; ++i) {
    const Vector3 geodetic = from_local_enu(anchor, Vector3(1000.0 * i, 0.0, 1000.0));
    rows[i].time = kT0 + 10.0 * i;
    rows[i].lat = geodetic.x();
    rows[i].lon = geodetic.y();
    rows[i].geoaltitude = geodetic.z();
    rows[i].velocity = 100.0;
    rows[i].heading = 90.0;
    rows[i].vertrate = 0.0;
    rows[i].lastposupdate = rows[i].time;
  }
  const RecordedTraffic traffic = read_opensky_states(write_states(rows), anchor, steps_of(1, 10));
  ASSERT_EQ(traffic.targets.size(), 1U);
  expect_near(traffic.targets[0].at(0).segment<3>(3), Vector3(100.0, 0.0, 0.0), 1e-9);
  // The second row's axes, 1 km east, are turned from the anchor's by 1000 m / R: its heading of
  // 90 degrees is 0.02 m/s north and down there, which the spline follows by 2 cm at 5 s.
  expect_near(traffic.targets[0].at(5).head<3>(), Vector3(500.0, 0.0, 1000.0), 0.05);
}

TEST(RecordedTraffic, AccelerationIsTheSplinesSecondDerivative) {
  const GeoAnchor anchor;
  // A climb straight up over the anchor at 2 m/s^2: a quadratic, which the cubic reproduces.
  std::vector<StateRow> rows;
  for (int i = 0; i <= 4; ++i) {
    const double t = 5.0 * i;
    StateRow row;
    row.time = kT0 + t;
    row.lat = anchor.latitude_deg;
    row.lon = anchor.longitude_deg;
    row.geoaltitude = 1000.0 + 5.0 * t + t * t;
    row.velocity = 0.0;
    row.heading = 0.0;
    row.vertrate = 5.0 + 2.0 * t;
    row.lastposupdate = row.time;
    rows.push_back(row);
  }
  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(0.5, 40));
  ASSERT_EQ(traffic.targets.size(), 1U);
  for (int step = 0; step <= 40; ++step) {
    const double t = 0.5 * step;
    const auto& state = traffic.targets[0].at(step);
    expect_near(state.head<3>(), Vector3(0.0, 0.0, 1000.0 + 5.0 * t + t * t - 480.0), 1e-6);
    expect_near(state.segment<3>(3), Vector3(0.0, 0.0, 5.0 + 2.0 * t), 1e-6);
    expect_near(state.tail<3>(), Vector3(0.0, 0.0, 2.0), 1e-6);
  }
}

TEST(RecordedTraffic, MissingVelocityIsEstimatedFromNeighbouringPositions) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows = straight_flight(anchor);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i % 2 == 0) rows[i].velocity.reset();
    if (i % 3 == 0) rows[i].heading.reset();
  }
  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(0.1, 600));
  ASSERT_EQ(traffic.targets.size(), 1U);
  for (int step = 0; step <= 600; step += 7) {
    const auto& state = traffic.targets[0].at(step);
    expect_near(state.head<3>(), kStart + 0.1 * step * kVelocity, 0.01);
    expect_near(state.segment<3>(3), kVelocity, 1e-3);
  }
}

TEST(RecordedTraffic, EachStepHearsTheNewestReportSinceTheStepBeforeCarriedForward) {
  const GeoAnchor anchor;
  // Positions sent at these times (s after kT0), each row written 3 s later; the one at 27 s
  // has no heading, so it gives no velocity and is no report; 41 and 43 fall in one step.
  std::vector<StateRow> rows;
  for (const double sent : {-3.0, 7.0, 17.0, 27.0, 37.0, 41.0, 43.0, 57.0}) {
    StateRow row = row_at(anchor, kT0 + sent, kStart + sent * kVelocity, kVelocity);
    row.time = kT0 + sent + 3.0;
    if (sent == 27.0) row.heading.reset();
    rows.push_back(row);
  }
  RecordedTrafficOptions options = steps_of(4.0, 15);
  options.start_time_s = kT0;
  const RecordedTraffic traffic = read_opensky_states(write_states(rows), anchor, options);
  ASSERT_EQ(traffic.targets.size(), 1U);
  const TargetTruth& aircraft = traffic.targets[0];
  EXPECT_EQ(aircraft.first_step, 0);
  EXPECT_EQ(aircraft.states.size(), 15U);  // steps 0..14: the last report is at 57 s
  // Step k hears what was sent in (4k - 4, 4k]: -3 at step 0, 7 at 2, 17 at 5, 37 at 10, the
  // newer 43 at 11; none at 7 (27 s gave no velocity) nor at 14 (57 s is after 56 s).
  const std::vector<std::pair<int, double>> heard = {
      {0, 3.0}, {2, 1.0}, {5, 3.0}, {10, 3.0}, {11, 1.0}};
  ASSERT_EQ(aircraft.broadcasts.size(), heard.size());
  for (std::size_t i = 0; i < heard.size(); ++i) {
    const auto [step, age] = heard[i];
    const HeardBroadcast& report = aircraft.broadcasts[i];
    EXPECT_EQ(report.step, step);
    EXPECT_NEAR(report.age_s, age, 1e-9) << "step " << step;
    // Carried forward along its own velocity to the step's time: on the straight line.
    expect_near(report.position_velocity.head<3>(), kStart + 4.0 * step * kVelocity, 1e-6);
    expect_near(report.position_velocity.tail<3>(), kVelocity, 1e-6);
    EXPECT_EQ(aircraft.broadcast_at(step), &report);
  }
  for (const int silent : {1, 3, 4, 6, 7, 8, 9, 12, 13, 14}) {
    EXPECT_EQ(aircraft.broadcast_at(silent), nullptr) << "step " << silent;
  }
}

TEST(RecordedTraffic, StaleGroundedAndPositionlessRowsAreSkippedAndCounted) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows = straight_flight(anchor);
  // Rows far off the line, each of which would bend the trajectory if it were used.
  StateRow stale = row_at(anchor, kT0 + 25.0, Vector3(0.0, 0.0, 9000.0), kVelocity);
  stale.lastposupdate = kT0 + 9.0;  // 16 s old
  StateRow grounded = row_at(anchor, kT0 + 35.0, Vector3(0.0, 0.0, 0.0), Vector3::Zero());
  grounded.onground = true;
  StateRow no_altitude = row_at(anchor, kT0 + 45.0, Vector3(0.0, 0.0, 9000.0), kVelocity);
  no_altitude.geoaltitude.reset();
  no_altitude.baroaltitude.reset();
  StateRow no_latitude = row_at(anchor, kT0 + 55.0, Vector3(0.0, 0.0, 9000.0), kVelocity);
  no_latitude.lat.reset();
  StateRow unknown_age = row_at(anchor, kT0 + 56.0, Vector3(0.0, 0.0, 9000.0), kVelocity);
  unknown_age.lastposupdate.reset();
  rows.insert(rows.begin() + 3, stale);
  rows.insert(rows.begin() + 5, grounded);
  rows.insert(rows.begin() + 7, no_altitude);
  rows.insert(rows.begin() + 9, no_latitude);
  rows.insert(rows.begin() + 10, unknown_age);

  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(0.1, 600));
  EXPECT_EQ(traffic.rows, 12U);
  EXPECT_EQ(traffic.stale_rows, 2U);
  EXPECT_EQ(traffic.rows_on_ground, 1U);
  EXPECT_EQ(traffic.rows_without_position, 2U);
  ASSERT_EQ(traffic.targets.size(), 1U);
  for (int step = 0; step <= 600; step += 5) {
    expect_near(traffic.targets[0].at(step).head<3>(), kStart + 0.1 * step * kVelocity, 0.01);
  }
}

TEST(RecordedTraffic, AFreshEnoughRowIsPlacedAtItsLastPositionUpdate) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows = straight_flight(anchor);
  // In place of the sample at 20 s: written at 25 s with the position received at 22 s, within
  // the 15 s allowed. Placed at 25 s it would be 3 s * 170 m/s = 510 m off the line.
  StateRow late = row_at(anchor, kT0 + 22.0, kStart + 22.0 * kVelocity, kVelocity);
  late.time = kT0 + 25.0;
  rows[2] = late;
  // The same position again, written at 26 s: nothing new.
  StateRow repeated = late;
  repeated.time = kT0 + 26.0;
  rows.insert(rows.begin() + 3, repeated);

  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(1.0, 60));
  EXPECT_EQ(traffic.stale_rows, 0U);
  EXPECT_EQ(traffic.repeated_position_rows, 1U);
  ASSERT_EQ(traffic.targets.size(), 1U);
  for (int step = 0; step <= 60; ++step) {
    expect_near(traffic.targets[0].at(step).head<3>(), kStart + step * kVelocity, 1e-3);
  }
}

TEST(RecordedTraffic, AltitudeFallsBackToTheOtherKindWhereOneIsEmpty) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows = straight_flight(anchor);
  rows[2].geoaltitude.reset();  // barometric, 40 m high, at 20 s
  // 40 m along the aircraft's vertical, a few kilometres off, is 40 m less a few micrometres
  // along the anchor's.
  constexpr double kTolerance = 1e-4;

  RecordedTraffic traffic = read_opensky_states(write_states(rows), anchor, steps_of(10.0, 6));
  ASSERT_EQ(traffic.targets.size(), 1U);
  EXPECT_NEAR(traffic.targets[0].at(1).z(), 3000.0, kTolerance);
  EXPECT_NEAR(traffic.targets[0].at(2).z(), 3040.0, kTolerance);

  RecordedTrafficOptions barometric = steps_of(10.0, 6);
  barometric.use_geometric_altitude = false;
  traffic = read_opensky_states(write_states(rows), anchor, barometric);
  ASSERT_EQ(traffic.targets.size(), 1U);
  EXPECT_NEAR(traffic.targets[0].at(1).z(), 3040.0, kTolerance);
  EXPECT_NEAR(traffic.targets[0].at(2).z(), 3040.0, kTolerance);
}

TEST(RecordedTraffic, AGapLongerThanThirtySecondsSplitsTheAircraft) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows;
  for (const double t : {0.0, 10.0, 20.0, 60.0, 70.0, 90.0}) {  // gaps of 40 s, then 20 s
    rows.push_back(row_at(anchor, kT0 + t, kStart + t * kVelocity, kVelocity));
  }
  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(1.0, 100));
  ASSERT_EQ(traffic.targets.size(), 2U);
  EXPECT_EQ(traffic.targets[0].label, "3c6444");
  EXPECT_EQ(traffic.targets[0].first_step, 0);
  EXPECT_EQ(traffic.targets[0].states.size(), 21U);
  EXPECT_EQ(traffic.targets[1].label, "3c6444#2");
  EXPECT_EQ(traffic.targets[1].first_step, 60);
  EXPECT_EQ(traffic.targets[1].states.size(), 31U);
  EXPECT_FALSE(traffic.targets[0].present_at(40));
  EXPECT_FALSE(traffic.targets[1].present_at(40));
  expect_near(traffic.targets[1].at(80).head<3>(), kStart + 80.0 * kVelocity, 0.01);
}

TEST(RecordedTraffic, SingleSamplesAreDroppedAndTargetsSortedByLabel) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows;
  for (const double t : {0.0, 10.0, 20.0}) {
    for (const char* icao24 : {"c0ffee", "4ca7b3", "a1b2c3"}) {
      StateRow row = row_at(anchor, kT0 + t, kStart + t * kVelocity, kVelocity);
      row.icao24 = icao24;
      // a1b2c3 is seen once only.
      if (row.icao24 != "a1b2c3" || t == 10.0) rows.push_back(row);
    }
  }
  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(1.0, 20));
  EXPECT_EQ(traffic.single_sample_aircraft, 1U);
  ASSERT_EQ(traffic.targets.size(), 2U);
  EXPECT_EQ(traffic.targets[0].label, "4ca7b3");
  EXPECT_EQ(traffic.targets[1].label, "c0ffee");
}

// An aircraft's callsign is the first its rows give that air traffic's formats can carry (up to
// 8 of A-Z, 0-9 and space; lower case taken as upper case); none where no row gives one.
TEST(RecordedTraffic, EachAircraftTakesTheFirstCallsignItsRowsGive) {
  const GeoAnchor anchor;
  std::vector<StateRow> rows;
  for (const double t : {0.0, 10.0, 20.0}) {
    for (const char* icao24 : {"3c6444", "4ca7b3", "a1b2c3"}) {
      StateRow row = row_at(anchor, kT0 + t, kStart + t * kVelocity, kVelocity);
      row.icao24 = icao24;
      if (row.icao24 == "4ca7b3") row.callsign = t == 0.0 ? "" : t == 10.0 ? "ein12 " : "EIN99";
      if (row.icao24 == "a1b2c3") row.callsign = "N-123";  // no such character in the set
      rows.push_back(row);
    }
  }
  const RecordedTraffic traffic =
      read_opensky_states(write_states(rows), anchor, steps_of(1.0, 20));
  ASSERT_EQ(traffic.targets.size(), 3U);
  EXPECT_EQ(callsign_of(traffic.targets[0].identification), "DLH4AB");
  EXPECT_EQ(callsign_of(traffic.targets[1].identification), "EIN12");
  EXPECT_EQ(traffic.targets[2].identification, kNoIdentification);
}

TEST(RecordedTraffic, OnlyTheRunsWindowIsKept) {
  const GeoAnchor anchor;
  RecordedTrafficOptions options = steps_of(1.0, 15);
  options.start_time_s = kT0 + 30.0;  // steps at 30..45 s of a flight sampled 0..60 s
  const RecordedTraffic traffic =
      read_opensky_states(write_states(straight_flight(anchor)), anchor, options);
  ASSERT_EQ(traffic.targets.size(), 1U);
  EXPECT_EQ(traffic.targets[0].first_step, 0);
  EXPECT_EQ(traffic.targets[0].states.size(), 16U);
  expect_near(traffic.targets[0].at(15).head<3>(), kStart + 45.0 * kVelocity, 0.01);

  options.start_time_s = kT0 + 100.0;  // after the flight
  EXPECT_TRUE(
      read_opensky_states(write_states(straight_flight(anchor)), anchor, options).targets.empty());
}

TEST(RecordedTraffic, ColumnsAreFoundByNameInAnyOrder) {
  const GeoAnchor anchor;
  std::vector<std::string> lines{
      "lastposupdate,onground,icao24,geoaltitude,baroaltitude,vertrate,heading,velocity,lon,lat,"
      "time"};
  for (const StateRow& row : straight_flight(anchor)) {
    lines.push_back(fmt::format("{},False,{},{},,{},{},{},{},{},{}", *row.lastposupdate, row.icao24,
                                *row.geoaltitude, *row.vertrate, *row.heading, *row.velocity,
                                *row.lon, *row.lat, row.time));
  }
  const RecordedTraffic traffic = read_opensky_states(write_file(lines), anchor, steps_of(1, 60));
  ASSERT_EQ(traffic.targets.size(), 1U);
  expect_near(traffic.targets[0].at(33).head<3>(), kStart + 33.0 * kVelocity, 0.01);
  EXPECT_EQ(traffic.targets[0].identification, kNoIdentification) << "no callsign column";
}

/// Reading `path` throws a std::runtime_error that starts "<path>:<line>: " and holds each of
/// `words`.
void expect_error_at(const std::filesystem::path& path, int line,
                     const std::vector<std::string>& words) {
  try {
    read_opensky_states(path, GeoAnchor{}, steps_of(1.0, 10));
    ADD_FAILURE() << "no error for " << path;
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(fmt::format("{}:{}: ", path.string(), line), 0), 0U) << message;
    for (const std::string& word : words) {
      EXPECT_NE(message.find(word), std::string::npos) << "'" << word << "' in " << message;
    }
  }
}

TEST(RecordedTraffic, AMissingColumnIsNamedAtTheHeader) {
  std::string header(kOpenSkyHeader);
  header.replace(header.find("vertrate,"), 9, "");
  expect_error_at(write_file({header}), 1, {"vertrate"});
}

TEST(RecordedTraffic, AFieldThatIsNotANumberIsNamedWithItsLine) {
  std::vector<StateRow> rows = straight_flight(GeoAnchor{});
  std::string bad = csv_line(rows[1]);
  bad.replace(bad.find(fmt::format("{}", *rows[1].lat)), 3, "4x.");
  const std::filesystem::path path =
      write_file({std::string(kOpenSkyHeader), csv_line(rows[0]), bad});
  expect_error_at(path, 3, {"'lat'", "4x."});
}

TEST(RecordedTraffic, TimeGoingBackwardsIsRefusedAtItsLine) {
  std::vector<StateRow> rows = straight_flight(GeoAnchor{});
  std::swap(rows[2], rows[3]);
  expect_error_at(write_states(rows), 5, {"earlier", "time order"});  // the 20 s row
}

TEST(RecordedTraffic, ARowWithTheWrongNumberOfFieldsIsRefusedAtItsLine) {
  std::vector<StateRow> rows = straight_flight(GeoAnchor{});
  expect_error_at(
      write_file({std::string(kOpenSkyHeader), csv_line(rows[0]), csv_line(rows[1]) + ",extra"}), 3,
      {"16", "17"});
}

TEST(RecordedTraffic, AnEmptyOrMissingFileIsRefused) {
  expect_error_at(write_file({}), 1, {"empty"});
  expect_error_at(std::filesystem::path(::testing::TempDir()) / "skyfuse_no_such_file.csv", 1,
                  {"cannot open"});
}

TEST(RecordedTraffic, OptionsOutOfRangeAreRefused) {
  const std::filesystem::path path = write_states(straight_flight(GeoAnchor{}));
  EXPECT_THROW(read_opensky_states(path, GeoAnchor{}, steps_of(0.0, 10)), std::invalid_argument);
  EXPECT_THROW(read_opensky_states(path, GeoAnchor{}, steps_of(1.0, -1)), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
