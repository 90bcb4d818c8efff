// Ctrl-C and SIGTERM as a request to stop, the one way every program here takes them: the signal sets a flag (and
// keeps its number for the exit code) that loops and bounded waits check, instead of killing the process.
#pragma once

#include <atomic>

namespace lcm_control {

// Installs the handler for SIGINT and SIGTERM. Without restart_interrupted_calls (the default) a blocking call a
// signal interrupts returns EINTR, so a wait ends early; with it, the call resumes and only the flag tells.
void install_stop_signals(bool restart_interrupted_calls = false);
bool stop_requested();
int stop_signal();  // the signal that asked, 0 if none
// The flag itself, for a loop that takes a std::atomic<bool> to poll.
const std::atomic<bool>& stop_flag();
void request_stop(int sig);
// Clears the flag so that a shutdown can still talk to its peers; a second
// Ctrl-C during it sets the flag again and cuts it short. Returns the signal.
int clear_stop();

}  // namespace lcm_control
