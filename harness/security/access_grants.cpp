#include "security/access_grants.hpp"

#include <stdexcept>

#include "skyfuse/transport/security_folder.hpp"
#include "skyfuse/transport/topics.hpp"

namespace skyfuse::harness {
namespace {

using transport::TopicTraits;

template <typename T>
std::string topic() {
  return TopicTraits<T>::kName;
}

}  // namespace

AccessGrant access_grant(const std::string& identity) {
  const std::string tick = topic<wire::Tick>();
  const std::string measurement = topic<wire::Measurement>();
  const std::string increment = topic<wire::InformationIncrement>();
  const std::string partial = topic<wire::PartialSum>();
  const std::string track = topic<wire::TrackEstimate>();
  const std::string status = topic<wire::StationStatus>();

  if (identity == transport::kHarnessIdentity) {
    return {identity, {tick}, {track, measurement, status}, {}, {status}};
  }
  if (identity == transport::kCenterIdentity) {
    return {identity, {track, status}, {tick, measurement, status}, {status}, {}};
  }
  if (identity == transport::kObserverIdentity)
    return {identity, {}, {tick, track, status}, {}, {}};
  if (transport::is_station_identity(identity)) {
    return {identity,
            {increment, partial, measurement, track, status},
            {tick, increment, partial, status},
            {status},
            {}};
  }
  throw std::invalid_argument("no access grant defined for identity '" + identity + "'");
}

}  // namespace skyfuse::harness
