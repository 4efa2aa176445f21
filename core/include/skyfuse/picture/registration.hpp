#pragma once
/// \file
/// The registration: the part of the tracker that estimates each station's biases online and
/// corrects its detections by them (docs/registration.md). Each kind is one line of the
/// registry (registration.cpp) and its files under picture/registrations/; a scenario names one
/// (`tracker: {registration: {kind: least_squares}}`), none by default.

#include <span>
#include <string>
#include <string_view>

namespace skyfuse {

struct RegistrationConfig;

struct RegistrationKind {
  std::string_view name;  ///< as a scenario names it
  std::string_view summary;
  /// Whether it estimates anything: `none` takes every detection as its sensor gives it, and a
  /// picture without a registration computes the bits it computed before registration existed.
  bool estimates = false;
};

/// Every registration, in the order `skyfuse` lists them.
std::span<const RegistrationKind> registrations();
/// The registration a scenario names `name`; nullptr for none.
const RegistrationKind* find_registration(std::string_view name);
/// Their names, "none, least_squares", for a message.
std::string registration_names();
/// Whether `config` names a registration that estimates (one that is not `none`).
bool estimates_biases(const RegistrationConfig& config);

}  // namespace skyfuse
