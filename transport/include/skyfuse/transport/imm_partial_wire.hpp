#pragma once
/// \file
/// An IMM's sum in the tree exchange (tracking/imm_partial_sum.hpp) on the wire: one PartialSum
/// sample per mode, written in mode order by one writer (skyfuse_wire.idl says which fields),
/// and assembled back into one sum once its writer sent every mode. Values cross bit for bit,
/// as in wire_conversion.hpp, so every peer fuses the bits the aggregator formed.
///
/// A writer's samples arrive in the order written, so a mode out of order, or one whose
/// header, contributors or mode probabilities are not its sum's first mode's, is refused with
/// the sum it would have completed (out_of_range): nothing assembled mixes two sums.

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "skyfuse/tracking/imm_partial_sum.hpp"
#include "skyfuse/transport/partial_wire.hpp"

namespace skyfuse::transport {

/// Mode I of `sum` as the sample that carries it.
template <int I, typename... Modes>
wire::PartialSum mode_sum_to_wire(const ImmPartialSum<Modes...>& sum, const SumHeader& header) {
  constexpr int N = std::tuple_element_t<I, std::tuple<Modes...>>::kDim;
  PartialSum<N> mode;
  mode.sum = std::get<I>(sum.sums);
  mode.contributors = sum.contributors;
  mode.reference = std::get<I>(sum.references);
  wire::PartialSum sample = to_wire(mode, header);
  const LikelihoodTerms& terms = sum.terms[I];
  sample.mode(static_cast<std::uint32_t>(I));
  if (!sum.empty()) {
    const auto& p = sum.prior_probabilities;
    sample.prior_mode_probabilities(std::vector<double>(p.data(), p.data() + p.size()));
  }
  sample.weighted_innovation(terms.weighted_innovation);
  sample.log_det_noise(terms.log_det_noise);
  sample.measurement_dim(static_cast<std::uint32_t>(terms.measurement_dim));
  return sample;
}

/// Writes `sum` as its modes' samples, in mode order.
template <typename Writer, typename... Modes>
void write_sum(Writer& writer, const ImmPartialSum<Modes...>& sum, const SumHeader& header) {
  ImmPartialSum<Modes...>::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
    writer.write(mode_sum_to_wire<I>(sum, header));
  });
}

template <typename... Modes>
class SumAssembler<ImmPartialSum<Modes...>> {
 public:
  using Sum = ImmPartialSum<Modes...>;
  static constexpr int kModes = Sum::kModes;

  /// The sum whose last mode `sample` is, or null: while its writer's sum is still incomplete
  /// (`why` empty), or refused (`why` says why; that writer's incomplete sum is dropped too).
  const Sum* feed(const wire::PartialSum& sample, const WriterId& writer,
                  std::optional<DropKind>& why) {
    why.reset();
    const std::uint32_t mode = sample.mode();
    auto it = pending_.find(writer);
    if (mode == 0) {
      it = pending_.try_emplace(writer).first;  // a sum left incomplete is replaced
      if (!start(sample, it->second)) why = DropKind::kOutOfRange;
    } else if (it == pending_.end() || it->second.next_mode != mode ||
               !same_sum(sample, it->second)) {
      why = DropKind::kOutOfRange;
    }
    if (!why && !read_mode(sample, it->second.sum)) why = DropKind::kOutOfRange;
    if (why) {
      if (it != pending_.end()) pending_.erase(it);
      return nullptr;
    }
    if (++it->second.next_mode < static_cast<std::uint32_t>(kModes)) return nullptr;
    complete_ = std::move(it->second.sum);
    pending_.erase(it);
    return &complete_;
  }

 private:
  struct Pending {
    Sum sum;
    wire::PartialSum first;  // its first mode's sample, without the numbers: the header
    std::uint32_t next_mode = 0;
  };

  // A sum's first mode: its header, contributors and mode probabilities, which every later mode
  // repeats.
  static bool start(const wire::PartialSum& sample, Pending& pending) {
    pending.next_mode = 0;
    Sum& sum = pending.sum;
    sum.clear();
    sum.contributors.assign(sample.contributors().begin(), sample.contributors().end());
    if (sum.empty()) {
      if (!sample.prior_mode_probabilities().empty()) return false;
    } else {
      const auto p = unpack_vector<kModes>(sample.prior_mode_probabilities());
      if (!p) return false;
      sum.prior_probabilities = *p;
    }
    pending.first.run_id(sample.run_id());
    pending.first.step(sample.step());
    pending.first.station_id(sample.station_id());
    pending.first.kind(sample.kind());
    pending.first.cluster(sample.cluster());
    pending.first.contributors(sample.contributors());
    pending.first.prior_mode_probabilities(sample.prior_mode_probabilities());
    return true;
  }
  static bool same_sum(const wire::PartialSum& sample, const Pending& pending) {
    const wire::PartialSum& first = pending.first;
    return sample.run_id() == first.run_id() && sample.step() == first.step() &&
           sample.station_id() == first.station_id() && sample.kind() == first.kind() &&
           sample.cluster() == first.cluster() && sample.contributors() == first.contributors() &&
           sample.prior_mode_probabilities() == first.prior_mode_probabilities();
  }
  // The sample's mode into `sum`: false if its lengths are not that mode's.
  static bool read_mode(const wire::PartialSum& sample, Sum& sum) {
    bool read = false;
    Sum::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      if (sample.mode() != static_cast<std::uint32_t>(I)) return;
      constexpr int N = std::tuple_element_t<I, std::tuple<Modes...>>::kDim;
      const auto mode = partial_sum_from_wire<N>(sample);
      if (!mode) return;
      std::get<I>(sum.sums) = mode->sum;
      if (!mode->empty()) std::get<I>(sum.references) = mode->reference;
      constexpr std::uint32_t kMaxDim = 1U << 20;  // far above any sum's; an int on our side
      if (sample.measurement_dim() > kMaxDim) return;
      sum.terms[I] = {sample.weighted_innovation(), sample.log_det_noise(),
                      static_cast<int>(sample.measurement_dim())};
      read = true;
    });
    return read;
  }

  std::map<WriterId, Pending> pending_;  // by writer: the sum whose modes are arriving
  Sum complete_;
};

}  // namespace skyfuse::transport
