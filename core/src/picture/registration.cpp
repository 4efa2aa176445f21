#include "skyfuse/picture/registration.hpp"

#include <array>

#include "skyfuse/picture/tracker_config.hpp"

namespace skyfuse {
namespace {

// The registry: one line per registration (picture/registrations/).
constexpr std::array kRegistrations{
    RegistrationKind{"none", "every detection as its sensor gives it", false},
    RegistrationKind{"least_squares",
                     "each station's offsets and clock by recursive least squares against the "
                     "aircraft's own reports (else the other stations' tracks), considered in R",
                     true},
};

}  // namespace

std::span<const RegistrationKind> registrations() {
  return kRegistrations;
}

const RegistrationKind* find_registration(std::string_view name) {
  for (const RegistrationKind& r : kRegistrations) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

std::string registration_names() {
  std::string names;
  for (const RegistrationKind& r : kRegistrations) {
    if (!names.empty()) names += ", ";
    names += r.name;
  }
  return names;
}

bool estimates_biases(const RegistrationConfig& config) {
  const RegistrationKind* kind = find_registration(config.kind);
  return kind != nullptr && kind->estimates;
}

}  // namespace skyfuse
