#pragma once
// `skyfuse run --secure`: how a secure run gets past discovery on Fast DDS 2.9.
//
// Measured here: when the harness, the center and four stations start with DDS-Security, about
// one start in three leaves a pair of participants that never finish authenticating, or whose
// endpoints match but never pass data (the first round then times out), for as long as one
// waits - 30 s were tried - with no error from Fast DDS. A fresh start of every process succeeds
// as often as the first. So a secure run spends --discovery-timeout in attempts of at most
// kSecureAttemptS each, and after an attempt that stalled like this starts every process again.

#include "run/lockstep_driver.hpp"

namespace skyfuse::harness {

/// Long enough for a secure start on a loaded 2-core machine (about 1.4 s when it works).
inline constexpr double kSecureAttemptS = 6.0;

/// True if `aborted` says that the run stalled before its first round completed: discovery did
/// not complete (the harness's timeout, or a node's, seen as its status or its exit code), or
/// round 0 closed incomplete because some pair of processes never matched.
bool is_stalled_start(const RunAborted& aborted);

}  // namespace skyfuse::harness
