#pragma once
// Runs Debian's `openssl` command. Certificates are made rarely and by a tool every admin
// knows, so each step of `skyfuse certs` is one openssl command line a reader can rerun by hand.

#include <string>
#include <vector>

namespace skyfuse::harness {

/// Runs `openssl args...` and waits for it; throws std::runtime_error with openssl's own
/// message if it cannot start or exits non-zero.
void run_openssl(const std::vector<std::string>& args);

}  // namespace skyfuse::harness
