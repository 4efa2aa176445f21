#pragma once
/// \file
/// Which wire type travels on which topic, and the name of its QoS profiles. One line per
/// topic; everything else derives from these traits.

#include <skyfuse/wire/skyfuse_picturePubSubTypes.h>
#include <skyfuse/wire/skyfuse_wire.h>
#include <skyfuse/wire/skyfuse_wirePubSubTypes.h>

namespace skyfuse::transport {

template <typename T>
struct TopicTraits;

template <>
struct TopicTraits<wire::Tick> {
  using PubSubType = wire::TickPubSubType;
  static constexpr const char* kName = "skyfuse_tick";
};
template <>
struct TopicTraits<wire::Measurement> {
  using PubSubType = wire::MeasurementPubSubType;
  static constexpr const char* kName = "skyfuse_measurement";
};
template <>
struct TopicTraits<wire::InformationIncrement> {
  using PubSubType = wire::InformationIncrementPubSubType;
  static constexpr const char* kName = "skyfuse_increment";
};
template <>
struct TopicTraits<wire::PartialSum> {
  using PubSubType = wire::PartialSumPubSubType;
  static constexpr const char* kName = "skyfuse_partial";
};
template <>
struct TopicTraits<wire::PictureScan> {
  using PubSubType = wire::PictureScanPubSubType;
  static constexpr const char* kName = "skyfuse_picture_scan";
};
template <>
struct TopicTraits<wire::PictureBundle> {
  using PubSubType = wire::PictureBundlePubSubType;
  static constexpr const char* kName = "skyfuse_picture_bundle";
};
template <>
struct TopicTraits<wire::PictureState> {
  using PubSubType = wire::PictureStatePubSubType;
  static constexpr const char* kName = "skyfuse_picture_state";
};
template <>
struct TopicTraits<wire::PictureRound> {
  using PubSubType = wire::PictureRoundPubSubType;
  static constexpr const char* kName = "skyfuse_picture_round";
};
template <>
struct TopicTraits<wire::TrackEstimate> {
  using PubSubType = wire::TrackEstimatePubSubType;
  static constexpr const char* kName = "skyfuse_track";
};
template <>
struct TopicTraits<wire::Echo> {
  using PubSubType = wire::EchoPubSubType;
  static constexpr const char* kName = "skyfuse_echo";
};
template <>
struct TopicTraits<wire::StationStatus> {
  using PubSubType = wire::StationStatusPubSubType;
  static constexpr const char* kName = "skyfuse_status";
};

}  // namespace skyfuse::transport
