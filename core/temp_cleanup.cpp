#include "core/temp_cleanup.h"

#include <pthread.h>
#include <cstdio>
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
  // Held until the process ends: the run's other threads, failing because their folder is gone,
  // wait in wait_for_interrupt_cleanup instead of exiting before the removal is done.
  move_mutex().lock();
  {
    std::set<std::string> paths;
    {
      const std::lock_guard<std::mutex> lock(set_mutex());
      paths = temporaries();
    }
    // Each one first renamed away (PATH.removing), so that the run, still working in other
    // threads, can no longer create files in it; then removed.
    for (const std::string& p : paths) {
      const std::string tomb = p + ".removing";
      std::error_code ec;
      if (::rename(p.c_str(), tomb.c_str()) == 0) {
        for (int pass = 0; pass < 3 && std::filesystem::exists(std::filesystem::symlink_status(tomb, ec)); ++pass)
          std::filesystem::remove_all(tomb, ec);
      } else {
        std::filesystem::remove_all(p, ec);
      }
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

void wait_for_interrupt_cleanup() { const std::lock_guard<std::mutex> wait(move_mutex()); }

void install_interrupt_cleanup() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread(wait_and_clean).detach();
}

}  // namespace shadowlab
