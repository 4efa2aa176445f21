// The writer of a picture's tracks (kPictureTrackProfile) holds at most kMaxPictureTracks
// instances; a track the picture dropped is unregistered, and its place must be free again, or
// a long run whose tentative tracks come and go would exhaust it and the node's write fail.
#include <gtest/gtest.h>

#include "skyfuse/transport/dds_node.hpp"
#include "transport/node_config_of.hpp"

namespace skyfuse::transport {
namespace {

using test::config_of;

wire::TrackEstimate track(std::uint64_t id) {
  wire::TrackEstimate sample;
  sample.run_id(1);
  sample.step(0);
  sample.track_id(id);
  sample.source_id(1);
  sample.x(std::vector<double>(6, 0.0));
  sample.covariance(std::vector<double>(21, 0.0));
  return sample;
}

TEST(PictureTrackWriter, ADroppedTracksPlaceIsFreedForTheNext) {
  DdsNode node(config_of("picture-tracks-freed", 224));
  Writer<wire::TrackEstimate> writer =
      node.make_writer<wire::TrackEstimate>({}, kPictureTrackProfile);
  // Twice the writer's instances, each written and dropped in turn.
  for (std::uint64_t id = 1; id <= 2 * kMaxPictureTracks + 1; ++id) {
    const wire::TrackEstimate sample = track(id);
    ASSERT_NO_THROW(writer.write(sample)) << "track " << id;
    ASSERT_NO_THROW(writer.unregister(sample)) << "track " << id;
  }
}

TEST(PictureTrackWriter, TracksKeptBeyondTheLimitAreAnErrorNotASilentLoss) {
  DdsNode node(config_of("picture-tracks-limit", 225));
  Writer<wire::TrackEstimate> writer =
      node.make_writer<wire::TrackEstimate>({}, kPictureTrackProfile);
  for (std::uint64_t id = 1; id <= kMaxPictureTracks; ++id) {
    ASSERT_NO_THROW(writer.write(track(id))) << "track " << id;
  }
  EXPECT_THROW(writer.write(track(kMaxPictureTracks + 1)), DdsError);
}

}  // namespace
}  // namespace skyfuse::transport
