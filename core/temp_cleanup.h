#pragma once
// Temporaries (a run's staging folder, a file's .partial-PID) that must not outlive an
// interrupted run. A failing run removes them by their owners' destructors; SIGINT, SIGTERM and
// SIGHUP are taken by a thread of their own (sigwait, outside signal context) that removes every
// registered temporary and then ends the process by the signal's default action, so the exit
// status still says which signal ended it.
#include <mutex>
#include <string>

namespace shadowlab {

// Registers a file or folder (removed recursively) to remove on an interrupt.
void register_temporary(const std::string& path);
void unregister_temporary(const std::string& path);

// Held while a run moves its outputs into place: an interrupt waits until the move is done, so
// it never removes a half-moved set (the process still ends by the signal then).
std::unique_lock<std::mutex> hold_interrupts();

// Returns at once, unless an interrupt's cleanup is under way: then it never returns (the
// process ends by the signal). The programs call it before they report an error or exit, so
// an error caused by the cleanup (their staging folder gone) is not reported as the run's.
void wait_for_interrupt_cleanup();

// Blocks the three signals in the calling thread (and so in every thread it starts later) and
// starts the thread that waits for them. Call first thing in main; a second call does nothing.
void install_interrupt_cleanup();

}  // namespace shadowlab
