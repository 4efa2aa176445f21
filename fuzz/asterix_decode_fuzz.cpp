// Fuzz target: decode_datagram on arbitrary bytes, as a UDP feed of ASTERIX would bring them.
// It must never crash or read outside the input (ASan, UBSan), must count every block it
// cannot read, and what it accepts must be stable: a decoded track, plot or report that the
// encoder writes again must encode to the same bytes after a second decode (the decoder's
// values are ones the encoder writes back unchanged).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "skyfuse/asterix/datagram.hpp"

namespace {

namespace ax = skyfuse::asterix;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "asterix_decode_fuzz: %s\n", what);
  std::abort();
}

// encode(decode(encode(value))) == encode(value), for every value the encoder takes.
template <typename T, typename Encode, typename Pick>
void expect_stable(const std::vector<T>& values, Encode encode, Pick pick) {
  for (const auto& value : values) {
    const auto once = encode(std::span<const T>(&value, 1));
    if (!once) continue;  // decoded values the encoder refuses (e.g. beyond the standard's range)
    const auto again = ax::decode_datagram(once.bytes);
    const auto& decoded = pick(again);
    if (decoded.size() != 1 || again.refusals.total() != 0) {
      finding("a record the encoder wrote was not decoded back");
    }
    const auto twice = encode(std::span<const T>(decoded.data(), 1));
    if (!twice || twice.bytes != once.bytes) finding("a decoded value does not re-encode alike");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto decoded = ax::decode_datagram(std::span<const std::uint8_t>(data, size));
  const std::size_t records = decoded.tracks.size() + decoded.plots.size() + decoded.reports.size();
  // A block costs 3 octets, a record at least one (its FSPEC).
  if (records > size) finding("more records than octets");
  expect_stable(
      decoded.tracks, [](auto v) { return ax::encode_cat062(v); },
      [](const ax::Decoded& d) -> const auto& { return d.tracks; });
  expect_stable(
      decoded.plots, [](auto v) { return ax::encode_cat048(v); },
      [](const ax::Decoded& d) -> const auto& { return d.plots; });
  expect_stable(
      decoded.reports, [](auto v) { return ax::encode_cat021(v); },
      [](const ax::Decoded& d) -> const auto& { return d.reports; });
  return 0;
}
