#pragma once
/// \file
/// The digest of a picture: its track count, then every track in ascending id with its id,
/// status and estimate, bit for bit. TrackTable::digest is it for a node's own picture; a
/// reader that received the tracks (a PictureRound, the skyfuse_track topic) computes it from
/// them to know it holds that node's picture.

#include <cstddef>
#include <cstdint>

#include "skyfuse/core/bit_digest.hpp"
#include "skyfuse/picture/track.hpp"

namespace skyfuse {

class PictureDigest {
 public:
  explicit PictureDigest(std::size_t tracks) { digest_.add(static_cast<std::uint64_t>(tracks)); }

  /// The next track, in ascending id.
  template <typename Mean, typename Covariance>
  void add(TrackId id, TrackStatus status, const Mean& mean, const Covariance& covariance) {
    digest_.add(id);
    digest_.add(static_cast<std::uint64_t>(status));
    digest_.add(mean);
    digest_.add(covariance);
  }

  /// The address of the track added last, for a track that holds one: a picture without
  /// addresses digests as it did before there were any.
  void add_address(std::uint32_t address) { digest_.add(static_cast<std::uint64_t>(address)); }
  std::uint64_t value() const { return digest_.value(); }

 private:
  BitDigest digest_;
};

/// The digest of a picture without tracks: a restarted station's, or every node's before the
/// first track.
inline std::uint64_t empty_picture_digest() {
  return PictureDigest(0).value();
}

}  // namespace skyfuse
