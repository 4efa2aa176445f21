#include "skyfuse/transport/shutdown.hpp"

#include <csignal>

namespace skyfuse::transport {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int signal) {
  g_signal = signal;
}

}  // namespace

void install_shutdown_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool shutdown_requested() {
  return g_signal != 0;
}
int shutdown_signal() {
  return g_signal;
}

}  // namespace skyfuse::transport
