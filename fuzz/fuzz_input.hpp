#pragma once
// Turns fuzz input bytes into the numbers of a sample, the way a DDS sample carries them: each
// double is eight raw bytes (so NaN, Inf, denormals and huge values are all one mutation away),
// and a symmetric matrix is its upper triangle, mirrored, as on the wire.

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "skyfuse/core/types.hpp"

namespace skyfuse::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  /// The next byte; 0 once the input is used up.
  std::uint8_t byte() {
    if (size_ == 0) return 0;
    --size_;
    return *data_++;
  }

  /// The next eight bytes as a double; missing bytes are zero, so a short input is still a
  /// sample (with zeros at the end) rather than a wasted run.
  double number() {
    unsigned char bytes[sizeof(double)] = {};
    const std::size_t n = size_ < sizeof bytes ? size_ : sizeof bytes;
    std::memcpy(bytes, data_, n);
    data_ += n;
    size_ -= n;
    double value = 0.0;
    std::memcpy(&value, bytes, sizeof value);
    return value;
  }

  template <int N>
  Vector<N> vector() {
    Vector<N> v;
    for (int i = 0; i < N; ++i) v(i) = number();
    return v;
  }

  /// Row by row over the upper triangle, mirrored below.
  template <int N>
  Covariance<N> symmetric() {
    Covariance<N> m;
    for (int r = 0; r < N; ++r) {
      for (int c = r; c < N; ++c) {
        m(r, c) = number();
        m(c, r) = m(r, c);
      }
    }
    return m;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

}  // namespace skyfuse::fuzz
