// The three UAPs, FRN by FRN, with each item's shape (and a compound's subfields, in order),
// from EUROCONTROL's specifications: CAT062 ed. 1.19 (Part 9), CAT048 ed. 1.31 (Part 4),
// CAT021 ed. 2.6 (Part 12). Only lengths matter here; the meaning of the items this library
// reads is in the category's encoder and decoder.
#include "skyfuse/asterix/uap.hpp"

#include <array>

namespace skyfuse::asterix {
namespace {

using Kind = ItemFormat::Kind;

constexpr ItemFormat fixed(std::uint8_t octets) {
  return {Kind::fixed, octets, {}};
}
constexpr ItemFormat extended(std::uint8_t max_parts) {
  return {Kind::extended, max_parts, {}};
}
constexpr ItemFormat repetitive(std::uint8_t element) {
  return {Kind::repetitive, element, {}};
}
constexpr ItemFormat repetitive_fx(std::uint8_t element) {
  return {Kind::repetitive_fx, element, {}};
}
constexpr ItemFormat explicit_len() {
  return {Kind::explicit_len, 0, {}};
}
constexpr ItemFormat compound(std::span<const ItemFormat> subfields) {
  return {Kind::compound, 0, subfields};
}
constexpr UapEntry spare() {
  return {0, {}};
}

template <std::size_t N>
constexpr std::array<ItemFormat, N> one_octet_subfields() {
  std::array<ItemFormat, N> subfields{};
  for (auto& s : subfields) s = fixed(1);
  return subfields;
}

// ---- CAT062 ed. 1.19 ----
// I062/380 Aircraft Derived Data: 28 subfields, ADR (#1) first.
constexpr std::array<ItemFormat, 28> k062_380{fixed(3),    fixed(6),       fixed(2), fixed(2),
                                              fixed(2),    fixed(2),       fixed(2),  // ADR..FSS
                                              extended(1), repetitive(15), fixed(2), fixed(2),
                                              fixed(7),    fixed(2),       fixed(2),  // TIS..GVR
                                              fixed(2),    fixed(2),       fixed(2), fixed(2),
                                              fixed(1),    fixed(8),       fixed(1),  // RAN..EMC
                                              fixed(6),    fixed(2),       fixed(1), repetitive(8),
                                              fixed(2),    fixed(2),       fixed(2)};  // POS..BPS
// I062/290 System Track Update Ages: TRK PSR SSR MDS ADS(2) ES VDL UAT LOP MLT.
constexpr std::array<ItemFormat, 10> k062_290{fixed(1), fixed(1), fixed(1), fixed(1), fixed(2),
                                              fixed(1), fixed(1), fixed(1), fixed(1), fixed(1)};
// I062/295 Track Data Ages: 31 one-octet ages.
constexpr auto k062_295 = one_octet_subfields<31>();
// I062/390 Flight Plan Related Data: TAG CSN IFI FCT TAC WTC DEP DST RDS CFL CTL TOD AST STS
// STD STA PEM PEC.
constexpr std::array<ItemFormat, 18> k062_390{
    fixed(2), fixed(7), fixed(4),      fixed(1), fixed(4), fixed(1), fixed(4), fixed(4), fixed(3),
    fixed(2), fixed(2), repetitive(4), fixed(6), fixed(1), fixed(7), fixed(7), fixed(2), fixed(7)};
// I062/110 Mode 5 Data Reports and Extended Mode 1 Code: SUM PMN POS GA EM1 TOS XP.
constexpr std::array<ItemFormat, 7> k062_110{fixed(1), fixed(4), fixed(6), fixed(2),
                                             fixed(2), fixed(1), fixed(1)};
// I062/500 Estimated Accuracies: APC COV APW AGA ABA ATV AA ARC.
constexpr std::array<ItemFormat, 8> k062_500{fixed(4), fixed(2), fixed(4), fixed(1),
                                             fixed(1), fixed(2), fixed(2), fixed(1)};
// I062/340 Measured Information: SID POS HEIGHT MDC MDA TYP.
constexpr std::array<ItemFormat, 6> k062_340{fixed(2), fixed(4), fixed(2),
                                             fixed(2), fixed(2), fixed(1)};

constexpr std::array<UapEntry, 35> k062{{
    {10, fixed(2)},                        // FRN 1
    spare(),                               // FRN 2
    {15, fixed(1)},                        // FRN 3
    {70, fixed(3)},                        // FRN 4
    {105, fixed(8)},                       // FRN 5
    {100, fixed(6)},                       // FRN 6
    {185, fixed(4)},                       // FRN 7
    {210, fixed(2)},                       // FRN 8
    {60, fixed(2)},                        // FRN 9
    {245, fixed(7)},                       // FRN 10
    {380, compound(k062_380)},             // FRN 11
    {40, fixed(2)},                        // FRN 12
    {80, extended(6)},                     // FRN 13
    {290, compound(k062_290)},             // FRN 14
    {200, fixed(1)},                       // FRN 15
    {295, compound(k062_295)},             // FRN 16
    {136, fixed(2)},                       // FRN 17
    {130, fixed(2)},                       // FRN 18
    {135, fixed(2)},                       // FRN 19
    {220, fixed(2)},                       // FRN 20
    {390, compound(k062_390)},             // FRN 21
    {270, extended(3)},                    // FRN 22
    {300, fixed(1)},                       // FRN 23
    {110, compound(k062_110)},             // FRN 24
    {120, fixed(2)},                       // FRN 25
    {510, repetitive_fx(3)},               // FRN 26
    {500, compound(k062_500)},             // FRN 27
    {340, compound(k062_340)},             // FRN 28
    spare(),                               // FRN 29
    spare(),                               // FRN 30
    spare(),                               // FRN 31
    spare(),                               // FRN 32
    spare(),                               // FRN 33
    {kReservedExpansion, explicit_len()},  // FRN 34
    {kSpecialPurpose, explicit_len()},     // FRN 35
}};

// ---- CAT048 ed. 1.31 ----
// I048/130 Radar Plot Characteristics: SRL SRR SAM PRL PAM RPD APD, one octet each.
constexpr auto k048_130 = one_octet_subfields<7>();
// I048/120 Radial Doppler Speed: CAL, RDS (REP × 6 octets).
constexpr std::array<ItemFormat, 2> k048_120{fixed(2), repetitive(6)};

constexpr std::array<UapEntry, 28> k048{{
    {10, fixed(2)},                        // FRN 1
    {140, fixed(3)},                       // FRN 2
    {20, extended(3)},                     // FRN 3
    {40, fixed(4)},                        // FRN 4
    {70, fixed(2)},                        // FRN 5
    {90, fixed(2)},                        // FRN 6
    {130, compound(k048_130)},             // FRN 7
    {220, fixed(3)},                       // FRN 8
    {240, fixed(6)},                       // FRN 9
    {250, repetitive(8)},                  // FRN 10
    {161, fixed(2)},                       // FRN 11
    {42, fixed(4)},                        // FRN 12
    {200, fixed(4)},                       // FRN 13
    {170, extended(2)},                    // FRN 14
    {210, fixed(4)},                       // FRN 15
    {30, repetitive_fx(1)},                // FRN 16
    {80, fixed(2)},                        // FRN 17
    {100, fixed(4)},                       // FRN 18
    {110, fixed(2)},                       // FRN 19
    {120, compound(k048_120)},             // FRN 20
    {230, fixed(2)},                       // FRN 21
    {260, fixed(7)},                       // FRN 22
    {55, fixed(1)},                        // FRN 23
    {50, fixed(2)},                        // FRN 24
    {65, fixed(1)},                        // FRN 25
    {60, fixed(2)},                        // FRN 26
    {kSpecialPurpose, explicit_len()},     // FRN 27
    {kReservedExpansion, explicit_len()},  // FRN 28
}};

// ---- CAT021 ed. 2.6 ----
// I021/220 Met Information: WS WD TMP TRB.
constexpr std::array<ItemFormat, 4> k021_220{fixed(2), fixed(2), fixed(2), fixed(1)};
// I021/110 Trajectory Intent: TIS (extended), TID (REP × 15 octets).
constexpr std::array<ItemFormat, 2> k021_110{extended(1), repetitive(15)};
// I021/295 Data Ages: 23 one-octet ages.
constexpr auto k021_295 = one_octet_subfields<23>();

constexpr std::array<UapEntry, 49> k021{{
    {10, fixed(2)},                        // FRN 1
    {40, extended(5)},                     // FRN 2
    {161, fixed(2)},                       // FRN 3
    {15, fixed(1)},                        // FRN 4
    {71, fixed(3)},                        // FRN 5
    {130, fixed(6)},                       // FRN 6
    {131, fixed(8)},                       // FRN 7
    {72, fixed(3)},                        // FRN 8
    {150, fixed(2)},                       // FRN 9
    {151, fixed(2)},                       // FRN 10
    {80, fixed(3)},                        // FRN 11
    {73, fixed(3)},                        // FRN 12
    {74, fixed(4)},                        // FRN 13
    {75, fixed(3)},                        // FRN 14
    {76, fixed(4)},                        // FRN 15
    {140, fixed(2)},                       // FRN 16
    {90, extended(4)},                     // FRN 17
    {210, fixed(1)},                       // FRN 18
    {70, fixed(2)},                        // FRN 19
    {230, fixed(2)},                       // FRN 20
    {145, fixed(2)},                       // FRN 21
    {152, fixed(2)},                       // FRN 22
    {200, fixed(1)},                       // FRN 23
    {155, fixed(2)},                       // FRN 24
    {157, fixed(2)},                       // FRN 25
    {160, fixed(4)},                       // FRN 26
    {165, fixed(2)},                       // FRN 27
    {77, fixed(3)},                        // FRN 28
    {170, fixed(6)},                       // FRN 29
    {20, fixed(1)},                        // FRN 30
    {220, compound(k021_220)},             // FRN 31
    {146, fixed(2)},                       // FRN 32
    {148, fixed(2)},                       // FRN 33
    {110, compound(k021_110)},             // FRN 34
    {16, fixed(1)},                        // FRN 35
    {8, fixed(1)},                         // FRN 36
    {271, extended(2)},                    // FRN 37
    {132, fixed(1)},                       // FRN 38
    {250, repetitive(8)},                  // FRN 39
    {260, fixed(7)},                       // FRN 40
    {400, fixed(1)},                       // FRN 41
    {295, compound(k021_295)},             // FRN 42
    spare(),                               // FRN 43
    spare(),                               // FRN 44
    spare(),                               // FRN 45
    spare(),                               // FRN 46
    spare(),                               // FRN 47
    {kReservedExpansion, explicit_len()},  // FRN 48
    {kSpecialPurpose, explicit_len()},     // FRN 49
}};

}  // namespace

std::span<const UapEntry> uap_cat062() {
  return k062;
}
std::span<const UapEntry> uap_cat048() {
  return k048;
}
std::span<const UapEntry> uap_cat021() {
  return k021;
}

unsigned frn_of(std::span<const UapEntry> uap, std::uint16_t item) {
  for (std::size_t i = 0; i < uap.size(); ++i) {
    if (uap[i].item == item && item != 0) return static_cast<unsigned>(i + 1);
  }
  return 0;
}

}  // namespace skyfuse::asterix
