// main() of the <target>_ci programs: a fuzz target's LLVMFuzzerTestOneInput on a reproducible
// sequence of inputs (ci_inputs.h), in place of libFuzzer's coverage-guided loop.
//
//   <target>_ci [--seed N] [--runs N] [--max-len N] [--timeout S] [--artifact-prefix P] PATH...
//
// Runs every seed file under PATH... (sorted), then --runs generated inputs, in one process under
// the sanitizers. On a crash, sanitizer report, abort (a conformance violation), or an input that
// runs longer than --timeout seconds, the input is written to <prefix>crash-<digest> or
// <prefix>timeout-<digest> and the process fails, as libFuzzer's artifacts are. Memory limits come
// from the sanitizer options (hard_rss_limit_mb, max_allocation_size_mb; run_ci.sh sets them).
// The last line says what ran: counts, seed and the digest of every input in order, so two runs
// can be compared.
#include <fcntl.h>
#include <sanitizer/common_interface_defs.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "ci_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using shadowcts::fuzzing::Bytes;

// What a signal handler needs to save the input that is running: filled before each input,
// read only with async-signal-safe calls.
struct Running {
  const Bytes* input = nullptr;
  char crash_path[4096] = {};
  char timeout_path[4096] = {};
  char label[256] = {};
  volatile std::sig_atomic_t saved = 0;
};
Running running;

void write_text(const char* text) {
  const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

void save_input(const char* path) {
  if (running.saved || !running.input) return;
  running.saved = 1;
  const int fd = open(path, O_CREAT | O_WRONLY | O_TRUNC, 0644);
  if (fd >= 0) {
    const Bytes& in = *running.input;
    std::size_t done = 0;
    while (done < in.size()) {
      const ssize_t n = write(fd, in.data() + done, in.size() - done);
      if (n <= 0) break;
      done += std::size_t(n);
    }
    close(fd);
  }
  write_text("ci-fuzz: failing input (");
  write_text(running.label);
  write_text(") written to ");
  write_text(path);
  write_text("\n");
}

void on_death() {
  save_input(running.crash_path);
}

void on_abort(int signal_number) {
  save_input(running.crash_path);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

void on_timeout(int) {
  write_text("ci-fuzz: timeout\n");
  save_input(running.timeout_path);
  _exit(70);
}

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "ci-fuzz: " << why
            << "\nusage: <target>_ci [--seed N] [--runs N] [--max-len N] [--timeout S] "
               "[--artifact-prefix P] PATH...\n";
  std::exit(2);
}

std::uint64_t number(const std::string& option, const char* text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || text[0] == '-')
    usage(option + ": not a non-negative integer: " + text);
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t seed = 1, runs = 1000, max_len = 65536, timeout = 20;
  std::string prefix = "./";
  std::vector<std::filesystem::path> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--seed")
      seed = number(arg, value());
    else if (arg == "--runs")
      runs = number(arg, value());
    else if (arg == "--max-len")
      max_len = number(arg, value());
    else if (arg == "--timeout")
      timeout = number(arg, value());
    else if (arg == "--artifact-prefix")
      prefix = value();
    else if (arg.rfind("--", 0) == 0)
      usage("unknown option " + arg);
    else
      paths.emplace_back(arg);
  }
  if (max_len == 0) usage("--max-len must be positive");

  std::vector<shadowcts::fuzzing::SeedInput> seeds;
  try {
    seeds = shadowcts::fuzzing::read_seed_inputs(paths, max_len);
  } catch (const std::exception& e) {
    usage(e.what());
  }
  shadowcts::fuzzing::CiInputGenerator generator(seeds, seed, max_len);
  shadowcts::fuzzing::InputDigest digest;

  __sanitizer_set_death_callback(on_death);
  std::signal(SIGABRT, on_abort);
  std::signal(SIGALRM, on_timeout);

  const auto start = std::chrono::steady_clock::now();
  const auto execute = [&](const Bytes& input, const std::string& label) {
    digest.add(input.data(), input.size());
    shadowcts::fuzzing::InputDigest own;
    own.add(input.data(), input.size());
    std::snprintf(running.crash_path, sizeof running.crash_path, "%scrash-%s", prefix.c_str(),
                  own.hex().c_str());
    std::snprintf(running.timeout_path, sizeof running.timeout_path, "%stimeout-%s", prefix.c_str(),
                  own.hex().c_str());
    std::snprintf(running.label, sizeof running.label, "%s", label.c_str());
    running.input = &input;
    alarm(static_cast<unsigned>(timeout));
    LLVMFuzzerTestOneInput(input.data(), input.size());
    alarm(0);
    running.input = nullptr;
  };
  for (const auto& s : generator.seeds()) execute(s.bytes, "seed " + s.path);
  for (std::uint64_t r = 0; r < runs; ++r)
    execute(generator.next(),
            "generated input " + std::to_string(r) + " of seed " + std::to_string(seed));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "ci-fuzz: ok: %zu seed inputs + %llu generated (seed %llu, max_len %llu), %.1f s, "
      "inputs digest %s\n",
      generator.seeds().size(), static_cast<unsigned long long>(runs),
      static_cast<unsigned long long>(seed), static_cast<unsigned long long>(max_len), seconds,
      digest.hex().c_str());
  return 0;
}
