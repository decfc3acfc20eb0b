#pragma once
// What an interrupted process (SIGINT, SIGTERM, SIGHUP: Ctrl-C, a CI job's timeout, a closed
// terminal) takes with it: its unfinished output folders and temporaries, and its worker processes'
// groups. Without this an interrupted run, export or certification left its unfinished folder
// behind.
#include <sys/types.h>

#include <cstdint>
#include <filesystem>

namespace shadowcts {

// Called first in main, before any thread starts: those signals are then taken by one thread, which
// removes and kills what is registered at that moment, says so on stderr, and ends the process as
// the signal would (exit status 128 + signal). A signal ignored when the process started (nohup, a
// background job of a non-interactive shell) stays ignored.
void handle_interruptions();

// While it lives, an interruption removes `path` (a file or a whole folder) or kills the process
// group `group`. Move-only; the destructor withdraws the registration (a finished output is kept).
class InterruptCleanup {
 public:
  static InterruptCleanup remove_path(std::filesystem::path path);
  static InterruptCleanup kill_group(pid_t group);
  InterruptCleanup(InterruptCleanup&& other) noexcept;
  InterruptCleanup& operator=(InterruptCleanup&& other) noexcept;
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;
  ~InterruptCleanup();

 private:
  explicit InterruptCleanup(std::uint64_t id) : id_(id) {}
  std::uint64_t id_ = 0;  // 0: nothing registered (moved from)
};

}  // namespace shadowcts
