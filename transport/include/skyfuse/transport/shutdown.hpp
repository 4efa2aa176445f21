#pragma once
/// \file
/// SIGINT/SIGTERM ask a node to stop: the handler only sets a flag, and the node's loop, which
/// wakes at least every few tens of milliseconds, winds down and deletes its DDS entities.

namespace skyfuse::transport {

void install_shutdown_handlers();
bool shutdown_requested();
/// The signal that asked for the stop, 0 if none.
int shutdown_signal();

}  // namespace skyfuse::transport
