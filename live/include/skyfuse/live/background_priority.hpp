#pragma once
// The live stream's threads run only on time the run leaves idle. A lock-step run is a chain of
// wake-ups from one process to the next; a viewer's thread taking a core at the wrong moment
// stalls the chain, so the stream's threads are scheduled SCHED_IDLE: they never preempt the
// stations, and with every core busy they wait (and the feed thins what it sends).

namespace skyfuse::live {

/// Puts the calling thread in the SCHED_IDLE class; false if the system refused.
bool lower_this_thread_to_idle_priority();

}  // namespace skyfuse::live
