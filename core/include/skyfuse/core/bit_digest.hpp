#pragma once
/// \file
/// A 64-bit digest of values' exact bits, for nodes to tell whether they hold the same state
/// without sending it: two states that differ in one bit of one double give different digests
/// but for a chance of 2^-64. Not a cryptographic hash (a rogue node is refused by other checks).

#include <Eigen/Core>
#include <bit>
#include <cstdint>

namespace skyfuse {

class BitDigest {
 public:
  void add(std::uint64_t word) {
    // FNV-1a over 64-bit words: each word folded in, then multiplied by the FNV prime.
    state_ = (state_ ^ word) * 0x100000001b3ULL;
  }
  void add(double value) { add(std::bit_cast<std::uint64_t>(value)); }
  /// Every entry, column by column.
  template <typename Derived>
  void add(const Eigen::DenseBase<Derived>& values) {
    for (Eigen::Index c = 0; c < values.cols(); ++c) {
      for (Eigen::Index r = 0; r < values.rows(); ++r) add(double{values.derived()(r, c)});
    }
  }

  /// The digest of everything added, in order: the state mixed once more (splitmix64's
  /// finalizer), so that nearby inputs give far-apart digests.
  std::uint64_t value() const {
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_ = 0xcbf29ce484222325ULL;  // FNV-1a's offset basis
};

}  // namespace skyfuse
