#pragma once
// Runs a load in a forked child under an address-space limit, so that a loader that allocates
// from an unchecked size fails the test (bad_alloc, or a crash) instead of taking the machine's
// memory. The child reports the InputError message it got through a pipe.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
#include <string>

#include "shadowcts/errors.h"

namespace shadowcts::testing {

struct ChildOutcome {
  bool input_error = false;  // the load threw InputError
  std::string message;       // its what(), or a description of what happened instead
  double seconds = 0.0;      // wall time of the child
};

inline ChildOutcome run_with_memory_limit(const std::function<void()>& load,
                                          std::size_t limit_bytes = std::size_t{768} << 20) {
  ChildOutcome outcome;
  int fds[2];
  if (pipe(fds) != 0) {
    outcome.message = "pipe() failed";
    return outcome;
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child == 0) {
    close(fds[0]);
    const rlimit limit{limit_bytes, limit_bytes};
    setrlimit(RLIMIT_AS, &limit);
    std::string report;
    char status = 'N';  // no exception
    try {
      load();
      report = "loaded without InputError";
    } catch (const InputError& e) {
      status = 'I';
      report = e.what();
    } catch (const std::exception& e) {
      status = 'E';
      report = std::string("other exception: ") + e.what();
    }
    report.insert(report.begin(), status);
    const char* data = report.data();
    std::size_t left = report.size();
    while (left > 0) {
      const ssize_t written = write(fds[1], data, left);
      if (written <= 0) break;
      data += written;
      left -= static_cast<std::size_t>(written);
    }
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string received;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;)
    received.append(buffer, static_cast<std::size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (WIFSIGNALED(status)) {
    outcome.message = "child killed by signal " + std::to_string(WTERMSIG(status));
  } else if (received.empty()) {
    outcome.message = "child reported nothing";
  } else {
    outcome.input_error = received[0] == 'I';
    outcome.message = received.substr(1);
  }
  return outcome;
}

}  // namespace shadowcts::testing
