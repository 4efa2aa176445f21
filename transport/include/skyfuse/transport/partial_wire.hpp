#pragma once
/// \file
/// A tree exchange's sum on the wire (skyfuse_wire.idl's PartialSum), and back. Values cross bit
/// for bit, as in wire_conversion.hpp, so a total fused by a member holds the bits its
/// aggregator formed.

#include <cstdint>
#include <optional>
#include <vector>

#include "skyfuse/fusion/partial_sum.hpp"
#include "skyfuse/transport/node_config.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

/// Where a sum sits in a round: who sent it, what it is, and the cluster it sums (for a total,
/// its sender's).
struct SumHeader {
  std::uint64_t run_id = 0;
  std::uint32_t step = 0;
  int station_id = 0;
  wire::SumKind kind = wire::CONTRIBUTION;
  std::uint32_t cluster = 0;
};

template <int N>
wire::PartialSum to_wire(const PartialSum<N>& sum, const SumHeader& header) {
  wire::PartialSum sample;
  sample.run_id(header.run_id);
  sample.step(header.step);
  sample.station_id(header.station_id);
  sample.kind(header.kind);
  sample.cluster(header.cluster);
  sample.contributors(std::vector<std::int32_t>(sum.contributors.begin(), sum.contributors.end()));
  sample.delta_information(pack_upper<N>(sum.sum.delta_information));
  sample.delta_vector(pack_vector<N>(sum.sum.delta_vector));
  if (!sum.empty()) {
    sample.prior_x(pack_vector<N>(sum.reference.mean));
    sample.prior_covariance(pack_upper<N>(sum.reference.covariance));
  }
  return sample;
}

/// The sum a sample carries for an N-state; nothing if its lengths are not N's (a sum that
/// counts nobody carries no reference, any other one). Its contents are the receiver's to
/// check (validation/partial_sum_checks.hpp).
template <int N>
std::optional<PartialSum<N>> partial_sum_from_wire(const wire::PartialSum& sample) {
  const auto dq = unpack_upper<N>(sample.delta_information());
  const auto dy = unpack_vector<N>(sample.delta_vector());
  if (!dq || !dy) return std::nullopt;
  PartialSum<N> sum;
  sum.contributors.assign(sample.contributors().begin(), sample.contributors().end());
  sum.sum.station_id = sum.empty() ? 0 : sum.contributors.front();
  sum.sum.delta_information = *dq;
  sum.sum.delta_vector = *dy;
  if (sum.empty()) {
    if (!sample.prior_x().empty() || !sample.prior_covariance().empty()) return std::nullopt;
    return sum;
  }
  const auto x = unpack_vector<N>(sample.prior_x());
  const auto p = unpack_upper<N>(sample.prior_covariance());
  if (!x || !p) return std::nullopt;
  sum.reference.mean = *x;
  sum.reference.covariance = *p;
  return sum;
}

/// Writes `sum` as the samples that carry it: one for a single model's (an IMM's:
/// imm_partial_wire.hpp).
template <int N, typename Writer>
void write_sum(Writer& writer, const PartialSum<N>& sum, const SumHeader& header) {
  writer.write(to_wire(sum, header));
}

/// Turns received samples back into sums (the tree exchange's input). A single model's sum
/// is one sample: the sum it carries, or why not - not this dimension's, or with an IMM's
/// fields.
template <typename Sum>
class SumAssembler;
template <int N>
class SumAssembler<PartialSum<N>> {
 public:
  /// The sum complete with `sample`, or null: `why` then says why it was refused (an IMM's
  /// assembler also answers null without a reason while a sum is still incomplete).
  const PartialSum<N>* feed(const wire::PartialSum& sample, const WriterId& /*writer*/,
                            std::optional<DropKind>& why) {
    why.reset();
    const bool single_model = sample.mode() == 0 && sample.prior_mode_probabilities().empty() &&
                              sample.weighted_innovation() == 0.0 &&
                              sample.log_det_noise() == 0.0 && sample.measurement_dim() == 0;
    auto sum = single_model ? partial_sum_from_wire<N>(sample) : std::nullopt;
    if (!sum) {
      why = DropKind::kOutOfRange;
      return nullptr;
    }
    sum_ = std::move(*sum);
    return &sum_;
  }

 private:
  PartialSum<N> sum_;
};

}  // namespace skyfuse::transport
