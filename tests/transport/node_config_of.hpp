#pragma once
// A test node's configuration: its name and its own domain. Each test has its own domain:
// ctest runs them as separate processes side by side, and in a shared domain one test's readers
// match the other's writers (CI saw exactly that).

#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::test {

inline transport::NodeConfig config_of(const char* name, int domain_id) {
  transport::NodeConfig config;
  config.domain_id = domain_id;
  config.name = name;
  return config;
}

}  // namespace skyfuse::test
