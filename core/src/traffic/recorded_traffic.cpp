#include "skyfuse/traffic/recorded_traffic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse {
namespace {

/// One usable row of an aircraft: where it was, at a time relative to step 0.
struct Sample {
  double time_s = 0.0;
  Vector3 position = Vector3::Zero();
  Vector3 velocity = Vector3::Zero();
  /// False where the row left velocity, heading or vertical rate empty: the velocity is then
  /// estimated from the neighbouring positions once all samples are in.
  bool velocity_known = false;
};

/// Where the file is being read, for error messages that let a person open it at the line.
struct Place {
  const std::filesystem::path& path;
  std::size_t line = 0;

  [[noreturn]] void fail(std::string_view what) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", path.string(), line, what));
  }
};

/// The columns the reader needs, by the names OpenSky's state-vector files give them.
enum Column : std::size_t {
  kTime,
  kIcao24,
  kLat,
  kLon,
  kVelocity,
  kHeading,
  kVertrate,
  kOnground,
  kGeoaltitude,
  kBaroaltitude,
  kLastposupdate,
  kColumnCount,
};
constexpr std::array<std::string_view, kColumnCount> kColumnNames = {
    "time",     "icao24",   "lat",         "lon",          "velocity",     "heading",
    "vertrate", "onground", "geoaltitude", "baroaltitude", "lastposupdate"};

/// Index of each required column in the file's rows, and how many fields a row has.
struct ColumnIndex {
  std::array<std::size_t, kColumnCount> of{};
  std::size_t fields = 0;
  /// OpenSky's `callsign`, where the file has it (the reader needs none).
  std::optional<std::size_t> callsign;
};

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

/// Splits a CSV line at its commas; a field in double quotes may hold commas, and "" inside it
/// is a quote. Fields are trimmed of surrounding blanks.
std::vector<std::string> split_fields(std::string_view line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back(trimmed(field));
      field.clear();
    } else {
      field += c;
    }
  }
  fields.emplace_back(trimmed(field));
  return fields;
}

ColumnIndex find_columns(const std::string& header, const Place& place) {
  std::string_view text = header;
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  const std::vector<std::string> names = split_fields(text);
  ColumnIndex index;
  index.fields = names.size();
  for (std::size_t column = 0; column < kColumnCount; ++column) {
    const auto found = std::find(names.begin(), names.end(), kColumnNames[column]);
    if (found == names.end()) {
      place.fail(
          fmt::format("the header has no column '{}' (an OpenSky state-vector file "
                      "names time, icao24, lat, lon, velocity, heading, vertrate, "
                      "onground, geoaltitude, baroaltitude and lastposupdate)",
                      kColumnNames[column]));
    }
    index.of[column] = static_cast<std::size_t>(found - names.begin());
  }
  if (const auto found = std::find(names.begin(), names.end(), "callsign"); found != names.end()) {
    index.callsign = static_cast<std::size_t>(found - names.begin());
  }
  return index;
}

/// The field's number, or nothing for an empty field (OpenSky's "unknown").
std::optional<double> optional_number(const std::vector<std::string>& fields,
                                      const ColumnIndex& columns, Column column,
                                      const Place& place) {
  const std::string& text = fields[columns.of[column]];
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end || !std::isfinite(value)) {
    place.fail(fmt::format("column '{}' is not a number: '{}'", kColumnNames[column], text));
  }
  return value;
}

double required_number(const std::vector<std::string>& fields, const ColumnIndex& columns,
                       Column column, const Place& place) {
  const std::optional<double> value = optional_number(fields, columns, column, place);
  if (!value) place.fail(fmt::format("column '{}' is empty", kColumnNames[column]));
  return *value;
}

/// OpenSky writes booleans as true/false (some exports as True/False or 1/0); empty is taken
/// as airborne, the reader's other checks still applying.
bool on_ground(const std::vector<std::string>& fields, const ColumnIndex& columns,
               const Place& place) {
  std::string text = fields[columns.of[kOnground]];
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (text == "true" || text == "1") return true;
  if (text.empty() || text == "false" || text == "0") return false;
  place.fail(
      fmt::format("column 'onground' is not true or false: '{}'", fields[columns.of[kOnground]]));
}

/// What one data row says, every field checked, before it is judged usable.
struct Row {
  double time_s = 0.0;
  std::string icao24;
  bool on_ground = false;
  std::optional<double> latitude_deg, longitude_deg, altitude_m;
  std::optional<double> speed_mps, heading_deg, vertical_rate_mps;
  std::optional<double> last_position_update_s;
  /// Its callsign, where the field holds one air traffic's formats can carry.
  Identification identification = kNoIdentification;
};

Row parse_row(const std::vector<std::string>& fields, const ColumnIndex& columns,
              const RecordedTrafficOptions& options, const Place& place) {
  if (fields.size() != columns.fields) {
    place.fail(fmt::format("expected {} fields, as the header names, but found {}", columns.fields,
                           fields.size()));
  }
  Row row;
  row.time_s = required_number(fields, columns, kTime, place);
  row.icao24 = fields[columns.of[kIcao24]];
  if (row.icao24.empty()) place.fail("column 'icao24' is empty");
  row.on_ground = on_ground(fields, columns, place);
  row.latitude_deg = optional_number(fields, columns, kLat, place);
  row.longitude_deg = optional_number(fields, columns, kLon, place);
  const std::optional<double> geometric = optional_number(fields, columns, kGeoaltitude, place);
  const std::optional<double> barometric = optional_number(fields, columns, kBaroaltitude, place);
  row.altitude_m = options.use_geometric_altitude ? (geometric ? geometric : barometric)
                                                  : (barometric ? barometric : geometric);
  row.speed_mps = optional_number(fields, columns, kVelocity, place);
  row.heading_deg = optional_number(fields, columns, kHeading, place);
  row.vertical_rate_mps = optional_number(fields, columns, kVertrate, place);
  row.last_position_update_s = optional_number(fields, columns, kLastposupdate, place);
  if (columns.callsign) {
    row.identification = identification_of(fields[*columns.callsign]).value_or(kNoIdentification);
  }
  return row;
}

/// The row's velocity in the anchor's frame: OpenSky's speed, heading and vertical rate are in
/// the aircraft's own east-north-up axes, which turn away from the anchor's with distance
/// (about a degree per 111 km).
Vector3 anchor_frame_velocity(const GeoAnchor& anchor, const Row& row) {
  const Vector3 local = enu_velocity(*row.speed_mps, *row.heading_deg, *row.vertical_rate_mps);
  const Matrix3 aircraft_to_ecef =
      ecef_to_enu_rotation(*row.latitude_deg, *row.longitude_deg).transpose();
  return ecef_to_enu_rotation(anchor.latitude_deg, anchor.longitude_deg) * aircraft_to_ecef * local;
}

/// Velocity of sample i from its neighbours' positions: the one-sided difference at the ends,
/// inside the slopes of both sides weighted by the other side's length (exact for a quadratic).
Vector3 finite_difference_velocity(const std::vector<Sample>& samples, std::size_t i) {
  const auto slope = [&](std::size_t a, std::size_t b) {
    return Vector3((samples[b].position - samples[a].position) /
                   (samples[b].time_s - samples[a].time_s));
  };
  if (i == 0) return slope(0, 1);
  if (i + 1 == samples.size()) return slope(i - 1, i);
  const double before = samples[i].time_s - samples[i - 1].time_s;
  const double after = samples[i + 1].time_s - samples[i].time_s;
  return (after * slope(i - 1, i) + before * slope(i, i + 1)) / (before + after);
}

/// [p; v; a] at `time_s` on the cubic Hermite segment between two samples.
Vector<kKinematicsDim> hermite_state(const Sample& from, const Sample& to, double time_s) {
  const double h = to.time_s - from.time_s;
  const double s = (time_s - from.time_s) / h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  const Vector3& p0 = from.position;
  const Vector3& p1 = to.position;
  const Vector3 m0 = h * from.velocity;
  const Vector3 m1 = h * to.velocity;
  Vector<kKinematicsDim> state;
  state.segment<3>(0) = (2.0 * s3 - 3.0 * s2 + 1.0) * p0 + (s3 - 2.0 * s2 + s) * m0 +
                        (-2.0 * s3 + 3.0 * s2) * p1 + (s3 - s2) * m1;
  state.segment<3>(3) = ((6.0 * s2 - 6.0 * s) * p0 + (3.0 * s2 - 4.0 * s + 1.0) * m0 +
                         (-6.0 * s2 + 6.0 * s) * p1 + (3.0 * s2 - 2.0 * s) * m1) /
                        h;
  state.segment<3>(6) = ((12.0 * s - 6.0) * p0 + (6.0 * s - 4.0) * m0 + (-12.0 * s + 6.0) * p1 +
                         (6.0 * s - 2.0) * m1) /
                        (h * h);
  return state;
}

// A step within a billionth of a step of a sample time counts as at it, so that the sums
// k * dt that land on sample times are not lost to rounding.
constexpr double kStepTolerance = 1e-9;

/// The reports a ground receiver hears from one presence at its steps first..last: at each
/// step, the newest sample sent since the step before whose row gave a velocity (a row without
/// one is no position-and-velocity report), carried forward to the step's time.
std::vector<HeardBroadcast> heard_broadcasts(const std::vector<Sample>& samples, int first,
                                             int last, double dt) {
  std::vector<HeardBroadcast> heard;
  std::size_t next = 0;
  for (int step = first; step <= last; ++step) {
    const double until_s = (static_cast<double>(step) + kStepTolerance) * dt;
    const Sample* newest = nullptr;
    for (; next < samples.size() && samples[next].time_s <= until_s; ++next) {
      const Sample& sample = samples[next];
      const bool since_step_before =
          sample.time_s > (static_cast<double>(step - 1) + kStepTolerance) * dt;
      if (since_step_before && sample.velocity_known) newest = &sample;
    }
    if (newest == nullptr) continue;
    HeardBroadcast report;
    report.step = step;
    report.age_s = std::max(0.0, static_cast<double>(step) * dt - newest->time_s);
    report.position_velocity.head<3>() = newest->position + report.age_s * newest->velocity;
    report.position_velocity.tail<3>() = newest->velocity;
    heard.push_back(report);
  }
  return heard;
}

/// Resamples one presence (at least two samples, velocities known) at the run's steps; empty
/// states where no step falls between its first and last sample.
TargetTruth resample(std::string label, const std::vector<Sample>& samples,
                     const RecordedTrafficOptions& options) {
  const double dt = options.time_step_s;
  const double first_k = std::ceil(samples.front().time_s / dt - kStepTolerance);
  const double last_k = std::floor(samples.back().time_s / dt + kStepTolerance);
  TargetTruth target;
  target.label = std::move(label);
  const double steps = static_cast<double>(options.steps);
  if (first_k > last_k || first_k > steps || last_k < 0.0) return target;
  const int first_step = static_cast<int>(std::max(first_k, 0.0));
  const int last_step = static_cast<int>(std::min(last_k, steps));
  target.first_step = first_step;
  target.states.reserve(static_cast<std::size_t>(last_step - first_step + 1));
  std::size_t segment = 0;
  for (int step = first_step; step <= last_step; ++step) {
    const double time_s =
        std::clamp(static_cast<double>(step) * dt, samples.front().time_s, samples.back().time_s);
    while (segment + 2 < samples.size() && samples[segment + 1].time_s <= time_s) ++segment;
    target.states.push_back(hermite_state(samples[segment], samples[segment + 1], time_s));
  }
  target.broadcasts = heard_broadcasts(samples, first_step, last_step, dt);
  return target;
}

void check_options(const RecordedTrafficOptions& options) {
  if (!(options.time_step_s > 0.0) || !std::isfinite(options.time_step_s)) {
    throw std::invalid_argument(
        fmt::format("read_opensky_states: time_step_s must be a positive number of seconds, not {}",
                    options.time_step_s));
  }
  if (options.steps < 0) {
    throw std::invalid_argument(
        fmt::format("read_opensky_states: steps must not be negative, not {}", options.steps));
  }
  if (!(options.max_staleness_s >= 0.0)) {
    throw std::invalid_argument(
        fmt::format("read_opensky_states: max_staleness_s must not be negative, not {}",
                    options.max_staleness_s));
  }
  if (std::isinf(options.start_time_s)) {
    throw std::invalid_argument("read_opensky_states: start_time_s must be a time or NaN");
  }
}

/// Splits one aircraft's samples into presences at gaps longer than kMaxRecordedSampleGapS.
std::vector<std::vector<Sample>> presences(const std::vector<Sample>& samples) {
  std::vector<std::vector<Sample>> split(1);
  for (const Sample& sample : samples) {
    if (!split.back().empty() &&
        sample.time_s - split.back().back().time_s > kMaxRecordedSampleGapS) {
      split.emplace_back();
    }
    split.back().push_back(sample);
  }
  return split;
}

}  // namespace

RecordedTraffic read_opensky_states(const std::filesystem::path& path, const GeoAnchor& anchor,
                                    const RecordedTrafficOptions& options) {
  check_options(options);
  Place place{path};
  place.line = 1;
  std::ifstream in(path);
  if (!in) place.fail("cannot open the file (does it exist, and may it be read?)");

  std::string line;
  std::optional<ColumnIndex> columns;
  while (!columns && std::getline(in, line)) {
    if (!trimmed(line).empty()) columns = find_columns(line, place);
    if (!columns) ++place.line;
  }
  if (!columns) {
    place.line = 1;
    place.fail("the file is empty: expected a header line naming the columns");
  }

  RecordedTraffic traffic;
  // Ordered by icao24, so that the targets come out in a fixed order whatever the file's.
  std::map<std::string, std::vector<Sample>> aircraft;
  // Each aircraft's callsign: the first its rows give.
  std::map<std::string, Identification> identifications;
  std::optional<double> previous_time_s;
  double start_time_s = options.start_time_s;
  while (std::getline(in, line)) {
    ++place.line;
    if (trimmed(line).empty()) continue;
    const Row row = parse_row(split_fields(line), *columns, options, place);
    ++traffic.rows;
    if (previous_time_s && row.time_s < *previous_time_s) {
      place.fail(
          fmt::format("time {} is earlier than the previous row's {}: rows must be in "
                      "time order",
                      row.time_s, *previous_time_s));
    }
    previous_time_s = row.time_s;
    if (std::isnan(start_time_s)) start_time_s = row.time_s;

    if (row.identification != kNoIdentification)
      identifications.try_emplace(row.icao24, row.identification);
    if (row.on_ground) {
      ++traffic.rows_on_ground;
      continue;
    }
    if (!row.latitude_deg || !row.longitude_deg || !row.altitude_m) {
      ++traffic.rows_without_position;
      continue;
    }
    if (!row.last_position_update_s ||
        row.time_s - *row.last_position_update_s > options.max_staleness_s) {
      ++traffic.stale_rows;
      continue;
    }
    Sample sample;
    sample.time_s = *row.last_position_update_s - start_time_s;
    std::vector<Sample>& samples = aircraft[row.icao24];
    if (!samples.empty() && sample.time_s <= samples.back().time_s) {
      ++traffic.repeated_position_rows;
      continue;
    }
    sample.position = to_local_enu(anchor, *row.latitude_deg, *row.longitude_deg, *row.altitude_m);
    sample.velocity_known = row.speed_mps && row.heading_deg && row.vertical_rate_mps;
    if (sample.velocity_known) sample.velocity = anchor_frame_velocity(anchor, row);
    samples.push_back(sample);
  }

  for (const auto& [icao24, samples] : aircraft) {
    int presence_number = 0;
    for (std::vector<Sample>& presence : presences(samples)) {
      ++presence_number;
      if (presence.size() < 2) {
        ++traffic.single_sample_aircraft;
        continue;
      }
      for (std::size_t i = 0; i < presence.size(); ++i) {
        if (!presence[i].velocity_known) {
          presence[i].velocity = finite_difference_velocity(presence, i);
        }
      }
      std::string label =
          presence_number == 1 ? icao24 : fmt::format("{}#{}", icao24, presence_number);
      TargetTruth target = resample(std::move(label), presence, options);
      if (const auto known = identifications.find(icao24); known != identifications.end()) {
        target.identification = known->second;
      }
      if (!target.states.empty()) traffic.targets.push_back(std::move(target));
    }
  }
  std::sort(traffic.targets.begin(), traffic.targets.end(),
            [](const TargetTruth& a, const TargetTruth& b) { return a.label < b.label; });
  return traffic;
}

}  // namespace skyfuse
