// The picture's digest: the same at two nodes holding the same picture, different when one
// bit of one track differs, or a track's id.
#include <gtest/gtest.h>

#include <cmath>

#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"

namespace skyfuse {
namespace {

using Model = ConstantVelocity3D;
using Sensor = RangeAzimuthElevation<Model::kDim>;
using Tracks = PeerModelTracks<Model, EkfIncrementRule>;
using Picture = PeerPicture<Tracks>;

Picture empty_picture() {
  const KnownStation<Model::kDim> station{
      1, Sensor(Vector3(0.0, 0.0, 0.0)), Covariance<3>::Identity(), 1.0, {}};
  return Picture(Tracks(Model(1.0, {0.5, 1.0}), Vector<Model::kDim>::Constant(100.0)), {station},
                 TrackerConfig{});
}

GaussianState<Model::kDim> an_estimate(double x) {
  GaussianState<Model::kDim> estimate;
  estimate.mean << x, 200.0, 300.0, 10.0, -5.0, 0.0;
  estimate.covariance = 4.0 * Covariance<Model::kDim>::Identity();
  estimate.covariance(0, 3) = estimate.covariance(3, 0) = 0.5;
  return estimate;
}

// Two tracks, predicted once.
Picture two_tracks(TrackId second_id, const GaussianState<Model::kDim>& second) {
  Picture picture = empty_picture();
  picture.add_known_track(3, an_estimate(100.0));
  picture.add_known_track(second_id, second);
  picture.predict();
  return picture;
}

TEST(PictureDigest, IsTheSameForTheSamePicture) {
  EXPECT_EQ(two_tracks(9, an_estimate(-50.0)).digest(), two_tracks(9, an_estimate(-50.0)).digest());
  EXPECT_EQ(empty_picture().digest(), empty_picture().digest());
}

TEST(PictureDigest, DiffersWhenOneBitOfOneTrackDiffers) {
  const std::uint64_t digest = two_tracks(9, an_estimate(-50.0)).digest();
  GaussianState<Model::kDim> one_ulp = an_estimate(-50.0);
  one_ulp.covariance(5, 5) = std::nextafter(one_ulp.covariance(5, 5), 10.0);
  EXPECT_NE(two_tracks(9, one_ulp).digest(), digest) << "a covariance entry, one ulp";
  EXPECT_NE(two_tracks(9, an_estimate(std::nextafter(-50.0, 0.0))).digest(), digest)
      << "a mean, one ulp";
  EXPECT_NE(two_tracks(10, an_estimate(-50.0)).digest(), digest) << "a track's id";
  EXPECT_NE(empty_picture().digest(), digest) << "no tracks";
}

}  // namespace
}  // namespace skyfuse
