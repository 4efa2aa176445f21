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
  // A run of many aircraft (docs/picture.md): scans, pictures, a whole picture to take.
  const std::string scan = topic<wire::PictureScan>();
  const std::string bundle = topic<wire::PictureBundle>();  // the tree's scans
  const std::string picture = topic<wire::PictureRound>();
  const std::string picture_state = topic<wire::PictureState>();

  if (identity == transport::kHarnessIdentity) {
    return {identity, {tick}, {track, measurement, status, picture}, {}, {status}, {}, {}};
  }
  if (identity == transport::kCenterIdentity) {
    return {identity, {track, status, picture}, {tick, measurement, status, scan}, {status}, {}, {},
            {bundle}};
  }
  if (identity == transport::kObserverIdentity)
    return {identity, {}, {tick, track, status, picture}, {}, {}, {}, {}};
  if (transport::is_station_identity(identity)) {
    return {identity,
            {increment, partial, measurement, track, status, scan, picture, picture_state},
            {tick, increment, partial, status, scan, picture_state},
            {status},
            {},
            {bundle},
            {bundle}};
  }
  throw std::invalid_argument("no access grant defined for identity '" + identity + "'");
}

}  // namespace skyfuse::harness
