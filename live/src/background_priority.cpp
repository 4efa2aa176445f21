#include "skyfuse/live/background_priority.hpp"

#include <pthread.h>
#include <sched.h>

namespace skyfuse::live {

bool lower_this_thread_to_idle_priority() {
  sched_param param{};
  param.sched_priority = 0;  // the only priority SCHED_IDLE takes
  return pthread_setschedparam(pthread_self(), SCHED_IDLE, &param) == 0;
}

}  // namespace skyfuse::live
