#pragma once
/// \file
/// The partition of the statuses by which a node reports, while the run goes on, what it
/// refused (NodePresence::report_refusals()). Only the harness reads it, and under
/// DDS-Security only stations and the center may publish in it (harness/security).
///
/// A status on the default partition reaches every node's status reader: 65 of them at
/// M = 64. Sent there, one report per node per round of refusals kept real-time M = 64 runs
/// from ever catching up after a late moment.

namespace skyfuse::transport {

inline constexpr const char* kRefusalReportsPartition = "skyfuse-refusal-reports";

}  // namespace skyfuse::transport
