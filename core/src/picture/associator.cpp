#include "skyfuse/picture/associator.hpp"

#include <array>

#include "skyfuse/picture/associators/gnn.hpp"
#include "skyfuse/picture/associators/jpda.hpp"

namespace skyfuse {
namespace {

// The registry: one line per associator.
constexpr std::array kAssociators{
    Associator{"gnn", "global nearest neighbour: one detection per track, least total NIS", false,
               false, &associate_gnn},
    Associator{"jpda", "joint probabilistic: every gated detection, weighed by its probability",
               true, true, &associate_jpda},
};

}  // namespace

std::span<const Associator> associators() {
  return kAssociators;
}

const Associator* find_associator(std::string_view name) {
  for (const Associator& a : kAssociators) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

std::string associator_names() {
  std::string names;
  for (const Associator& a : kAssociators) {
    if (!names.empty()) names += ", ";
    names += a.name;
  }
  return names;
}

}  // namespace skyfuse
