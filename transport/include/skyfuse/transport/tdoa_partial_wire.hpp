#pragma once
/// \file
/// The NCRKF's sum in the tree exchange (tracking/tdoa_partial_sum.hpp) on the wire: two
/// PartialSum samples written in turn by one writer, `mode` 0 the sum of all increments and 1 the
/// sum of the definite ones (skyfuse_wire.idl), assembled back into one sum from one writer's
/// pair. As for an IMM's sum (imm_partial_wire.hpp), a second sample with no first, or whose
/// header is not its first's, is refused with the sum it would have completed.

#include <map>
#include <optional>

#include "skyfuse/tracking/tdoa_partial_sum.hpp"
#include "skyfuse/transport/partial_wire.hpp"

namespace skyfuse::transport {

/// Writes `sum` as its two samples: all, then the definite ones.
template <typename Writer, int N>
void write_sum(Writer& writer, const TdoaPartialSum<N>& sum, const SumHeader& header) {
  writer.write(to_wire(static_cast<const PartialSum<N>&>(sum), header));
  wire::PartialSum definite = to_wire(sum.definite, header);
  definite.mode(1);
  writer.write(definite);
}

template <int N>
class SumAssembler<TdoaPartialSum<N>> {
 public:
  /// The sum whose second sample `sample` is, or null: while its writer's first is alone (`why`
  /// empty), or refused (`why` says why; that writer's first is dropped too).
  const TdoaPartialSum<N>* feed(const wire::PartialSum& sample, const WriterId& writer,
                                std::optional<DropKind>& why) {
    why = DropKind::kOutOfRange;
    const bool no_imm_fields = sample.prior_mode_probabilities().empty() &&
                               sample.weighted_innovation() == 0.0 &&
                               sample.log_det_noise() == 0.0 && sample.measurement_dim() == 0;
    auto part = no_imm_fields ? partial_sum_from_wire<N>(sample) : std::nullopt;
    auto it = pending_.find(writer);
    if (!part || sample.mode() > 1) {
      if (it != pending_.end()) pending_.erase(it);
      return nullptr;
    }
    if (sample.mode() == 0) {
      Pending& pending = pending_[writer];
      static_cast<PartialSum<N>&>(pending.sum) = std::move(*part);
      pending.header = sample;
      why.reset();
      return nullptr;
    }
    if (it == pending_.end() || !same_header(sample, it->second.header)) {
      if (it != pending_.end()) pending_.erase(it);
      return nullptr;
    }
    complete_ = std::move(it->second.sum);
    complete_.definite = std::move(*part);
    pending_.erase(it);
    why.reset();
    return &complete_;
  }

 private:
  struct Pending {
    TdoaPartialSum<N> sum;
    wire::PartialSum header;  // the first sample: run, step, sender, kind, cluster
  };
  static bool same_header(const wire::PartialSum& a, const wire::PartialSum& b) {
    return a.run_id() == b.run_id() && a.step() == b.step() && a.station_id() == b.station_id() &&
           a.kind() == b.kind() && a.cluster() == b.cluster();
  }

  std::map<WriterId, Pending> pending_;  // by writer: a sum whose first sample came
  TdoaPartialSum<N> complete_;
};

}  // namespace skyfuse::transport
