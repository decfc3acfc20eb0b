#include "interrupt_cleanup.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <variant>

namespace shadowcts {
namespace {

using Registered = std::variant<std::filesystem::path, pid_t>;

struct Registry {
  std::mutex mutex;
  std::map<std::uint64_t, Registered> entries;  // by registration, so cleanup runs in that order
  std::uint64_t next_id = 1;
};

// Never destroyed: the signal thread may still take it while the process exits.
Registry& registry() {
  static Registry& instance = *new Registry;
  return instance;
}

std::uint64_t add(Registered what) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  const std::uint64_t id = r.next_id++;
  r.entries.emplace(id, std::move(what));
  return id;
}

sigset_t interruption_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, signal);
  return set;
}

// Runs on the thread that took the signal; holds the registry's lock to the end, so nothing is
// registered or withdrawn meanwhile.
[[noreturn]] void end_interrupted(int signal) {
  Registry& r = registry();
  r.mutex.lock();
  // Workers first: they write into the folders removed next.
  for (const auto& [id, what] : r.entries)
    if (const pid_t* group = std::get_if<pid_t>(&what)) {
      ::kill(-*group, SIGKILL);
      ::kill(*group, SIGKILL);
    }
  std::string removed;
  for (const auto& [id, what] : r.entries)
    if (const auto* path = std::get_if<std::filesystem::path>(&what)) {
      std::error_code ec;
      if (!std::filesystem::exists(std::filesystem::symlink_status(*path, ec))) continue;
      // Twice: a thread still writing may have created a file in the folder meanwhile.
      std::filesystem::remove_all(*path, ec);
      std::filesystem::remove_all(*path, ec);
      removed += (removed.empty() ? " " : ", ") + path->string();
    }
  std::cerr << "\nshadowcts: interrupted (SIG" << ::sigabbrev_np(signal) << ")"
            << (removed.empty() ? std::string() : "; removed the unfinished" + removed) << "\n"
            << std::flush;
  ::signal(signal, SIG_DFL);
  sigset_t only;
  sigemptyset(&only);
  sigaddset(&only, signal);
  ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
  ::raise(signal);
  ::_exit(128 + signal);  // not reached: the default action of these signals ends the process
}

}  // namespace

void handle_interruptions() {
  static std::once_flag once;
  std::call_once(once, [] {
    const sigset_t set = interruption_signals();
    ::pthread_sigmask(SIG_BLOCK, &set, nullptr);
    try {
      std::thread([set] {
        int signal = 0;
        while (::sigwait(&set, &signal) != 0) {
        }
        end_interrupted(signal);
      }).detach();
    } catch (const std::system_error&) {
      // No thread to take them: the signals keep their default action, without the cleanup.
      ::pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
    }
  });
}

InterruptCleanup InterruptCleanup::remove_path(std::filesystem::path path) {
  return InterruptCleanup(add(std::move(path)));
}

InterruptCleanup InterruptCleanup::kill_group(pid_t group) {
  return InterruptCleanup(add(group));
}

InterruptCleanup::InterruptCleanup(InterruptCleanup&& other) noexcept
    : id_(std::exchange(other.id_, 0)) {}

InterruptCleanup& InterruptCleanup::operator=(InterruptCleanup&& other) noexcept {
  if (this != &other) {
    InterruptCleanup discarded(std::move(*this));
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

InterruptCleanup::~InterruptCleanup() {
  if (id_ == 0) return;
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  r.entries.erase(id_);
}

}  // namespace shadowcts
