#include "core/temp_cleanup.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <thread>

namespace shadowlab {
namespace {

// Two locks, always taken in this order: the move (held across a whole commit) and the set.
std::mutex& move_mutex() {
  static std::mutex m;
  return m;
}

std::mutex& set_mutex() {
  static std::mutex m;
  return m;
}

std::set<std::string>& temporaries() {
  static std::set<std::string> s;
  return s;
}

sigset_t interrupt_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  return set;
}

[[noreturn]] void wait_and_clean() {
  const sigset_t set = interrupt_signals();
  int sig = 0;
  while (sigwait(&set, &sig) != 0) {
  }
  {
    const std::lock_guard<std::mutex> move(move_mutex());
    std::set<std::string> paths;
    {
      const std::lock_guard<std::mutex> lock(set_mutex());
      paths = temporaries();
    }
    // Twice: a file the run was creating in a folder as it was removed.
    for (int pass = 0; pass < 2; ++pass)
      for (const std::string& p : paths) {
        std::error_code ec;
        std::filesystem::remove_all(p, ec);
      }
  }
  // The default action (the process ends, its status naming the signal), raised in this thread,
  // the one thread where the signal is no longer blocked.
  ::signal(sig, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, sig);
  pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  ::raise(sig);
  _exit(128 + sig);
}

}  // namespace

void register_temporary(const std::string& path) {
  const std::lock_guard<std::mutex> lock(set_mutex());
  temporaries().insert(path);
}

void unregister_temporary(const std::string& path) {
  const std::lock_guard<std::mutex> lock(set_mutex());
  temporaries().erase(path);
}

std::unique_lock<std::mutex> hold_interrupts() { return std::unique_lock<std::mutex>(move_mutex()); }

void install_interrupt_cleanup() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread(wait_and_clean).detach();
}

}  // namespace shadowlab
