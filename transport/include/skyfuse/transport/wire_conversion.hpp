#pragma once
/// \file
/// Conversion between wire samples and core types, at the edge of every process. Doubles are
/// copied bit for bit and symmetric matrices travel as their upper triangle, so a value that
/// crosses the wire is the value that was sent: the DDS path adds no rounding.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/transport/topics.hpp"
#include "skyfuse/transport/wire_configuration.hpp"

namespace skyfuse::transport {

/// Row-major upper triangle of a symmetric N x N matrix, N (N + 1) / 2 values.
template <int N>
void pack_upper(const Covariance<N>& m, double* out) {
  int k = 0;
  for (int r = 0; r < N; ++r) {
    for (int c = r; c < N; ++c) out[k++] = m(r, c);
  }
}
template <int N>
Covariance<N> unpack_upper(const double* in) {
  Covariance<N> m;
  int k = 0;
  for (int r = 0; r < N; ++r) {
    for (int c = r; c < N; ++c) m(r, c) = m(c, r) = in[k++];
  }
  return m;
}

wire::Measurement to_wire(const WireObservation& observation, std::uint64_t run_id,
                          std::uint32_t step);
WireObservation from_wire(const wire::Measurement& sample);

wire::InformationIncrement to_wire(const WireContribution& contribution, std::uint64_t run_id,
                                   std::uint32_t step);
WireContribution from_wire(const wire::InformationIncrement& sample);

wire::TrackEstimate to_wire(const WireEstimate& estimate, std::uint64_t run_id, std::uint32_t step,
                            int source_id, wire::TrackSource mode,
                            std::span<const int> contributors);
WireEstimate from_wire(const wire::TrackEstimate& sample);

}  // namespace skyfuse::transport
