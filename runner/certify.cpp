#include "certify.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "atomic_file.h"
#include "case_reproducer.h"
#include "case_shrinking.h"
#include "conformance_violation.h"
#include "fixtures/fuzz/fuzz_fixtures.h"
#include "interrupt_cleanup.h"
#include "junit_xml.h"
#include "machine_info.h"
#include "plugin_backend.h"
#include "report/html_report.h"
#include "run_record.h"
#include "sha256.h"
#include "shadowcts/backend_abi.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

extern char** environ;

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// Bytes for hashes: little-endian, fixed widths.

void put_u32(std::string& bytes, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) bytes += char((v >> (8 * k)) & 0xFF);
}
void put_u64(std::string& bytes, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) bytes += char((v >> (8 * k)) & 0xFF);
}
void put_float(std::string& bytes, float f) {
  std::uint32_t v;
  std::memcpy(&v, &f, 4);
  put_u32(bytes, v);
}
void put_double(std::string& bytes, double d) {
  std::uint64_t v;
  std::memcpy(&v, &d, 8);
  put_u64(bytes, v);
}
void put_vec3(std::string& bytes, const glm::vec3& v) {
  for (int k = 0; k < 3; ++k) put_float(bytes, v[k]);
}
void put_text(std::string& bytes, const std::string& text) {
  put_u64(bytes, text.size());
  bytes += text;
}

// ---------------------------------------------------------------------------------------------
// Reading JSON files.

ordered_json read_json(const fs::path& file, const std::string& what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), what, "cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  ordered_json j = ordered_json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(file.string(), what, "is not a JSON object");
  return j;
}

std::string quoted(const std::string& arg) {
  if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                            "0123456789-_./=:,+") == std::string::npos)
    return arg;
  std::string q = "'";
  for (char ch : arg) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

std::string joined_command(const std::vector<std::string>& args) {
  std::string line;
  for (const std::string& a : args) line += (line.empty() ? "" : " ") + quoted(a);
  return line;
}

// A name safe for a folder: [A-Za-z0-9._+-], others as '_'.
std::string folder_name(const std::string& name) {
  std::string safe;
  for (char ch : name)
    safe += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-' ||
             ch == '+')
                ? ch
                : '_';
  return safe.empty() || safe == "." || safe == ".." ? "_" + safe : safe;
}

// ---------------------------------------------------------------------------------------------
// Worker processes.

struct WorkerRun {
  enum class End { exited, signalled, timed_out, not_started } end = End::not_started;
  int code = 0;  // exit status or signal
  double wall_s = 0;
};

std::string self_executable() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot read /proc/self/exe: " + ec.message());
  return exe.string();
}

// Runs `args` (args[0] the program) with stdout and stderr into `log`, in its own process group,
// killing the group after `timeout_s`.
WorkerRun run_worker(const std::vector<std::string>& args, const fs::path& log, double timeout_s) {
  WorkerRun result;
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attributes);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  // The worker starts with no signal blocked: this process blocks the interruption signals in
  // every thread for the one that handles them (interrupt_cleanup.h).
  sigset_t no_signals;
  sigemptyset(&no_signals);
  posix_spawnattr_setsigmask(&attributes, &no_signals);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attributes, 0);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const auto start = Clock::now();
  const int error = ::posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (error != 0)
    throw std::runtime_error("cannot start a worker process (" + args[0] +
                             "): " + std::strerror(error));
  // Killed first when this process is interrupted, before the folders they write into are removed:
  // PR_SET_PDEATHSIG ends a worker only once this process is gone, and not what it started.
  const InterruptCleanup worker_group = InterruptCleanup::kill_group(pid);
  const auto deadline = start + std::chrono::duration<double>(timeout_s);
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) throw std::runtime_error("waitpid failed on a worker");
    if (Clock::now() >= deadline) {
      ::kill(-pid, SIGKILL);
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      result.end = WorkerRun::End::timed_out;
      result.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
      return result;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Anything the worker left behind in its group (it should have none) goes with it.
  ::kill(-pid, SIGKILL);
  result.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  if (WIFSIGNALED(status)) {
    result.end = WorkerRun::End::signalled;
    result.code = WTERMSIG(status);
  } else {
    result.end = WorkerRun::End::exited;
    result.code = WEXITSTATUS(status);
  }
  return result;
}

// The last non-empty line of a log, for reasons.
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last.size() > 300 ? last.substr(0, 300) + "..." : last;
}

// ---------------------------------------------------------------------------------------------
// One case x variant of a certification.

struct Entry {
  std::string case_name, variant;
  std::string verdict;  // Pass, Fail, QualityWarning, NotSupported, Crash, Timeout
  std::string reason;
  bool declared_not_supported = false;
  double time_ms = 0;
  ordered_json counters = ordered_json::object();
  std::string output_sha256;  // of the first run; empty when it produced none
  ordered_json runs = ordered_json::array();
  std::string folder;  // the first run's result folder, relative to the certification folder
  std::string record_name, output, algorithm, backend;
};

ordered_json entry_json(const Entry& e) {
  ordered_json j;
  j["case"] = e.case_name;
  j["variant"] = e.variant;
  j["verdict"] = e.verdict;
  j["reason"] = e.reason;
  j["declared_not_supported"] = e.declared_not_supported;
  j["time_ms"] = e.time_ms;
  j["counters"] = e.counters;
  j["output_sha256"] = e.output_sha256;
  j["runs"] = e.runs;
  j["folder"] = e.folder;
  j["record"] = {{"name", e.record_name},
                 {"output", e.output},
                 {"algorithm", e.algorithm},
                 {"backend", e.backend}};
  return j;
}

Entry entry_from_json(const ordered_json& j) {
  Entry e;
  e.case_name = j.at("case").get<std::string>();
  e.variant = j.at("variant").get<std::string>();
  e.verdict = j.at("verdict").get<std::string>();
  e.reason = j.at("reason").get<std::string>();
  e.declared_not_supported = j.at("declared_not_supported").get<bool>();
  e.time_ms = j.at("time_ms").get<double>();
  e.counters = j.at("counters");
  e.output_sha256 = j.at("output_sha256").get<std::string>();
  e.runs = j.at("runs");
  e.folder = j.at("folder").get<std::string>();
  const ordered_json& r = j.at("record");
  e.record_name = r.at("name").get<std::string>();
  e.output = r.at("output").get<std::string>();
  e.algorithm = r.at("algorithm").get<std::string>();
  e.backend = r.at("backend").get<std::string>();
  return e;
}

std::string run_end_text(const WorkerRun& run, double timeout_s) {
  switch (run.end) {
    case WorkerRun::End::timed_out: {
      std::ostringstream s;
      s << "no answer within the timeout of " << timeout_s << " s: the worker was killed";
      return s.str();
    }
    case WorkerRun::End::signalled:
      return "the worker was killed by signal " + std::to_string(run.code) + " (" +
             ::strsignal(run.code) + ")";
    case WorkerRun::End::exited:
      return "the worker exited with status " + std::to_string(run.code);
    case WorkerRun::End::not_started:
      break;
  }
  return "the worker did not start";
}

// Loads and validates the library in a worker process first, so that a library that crashes or
// hangs while it is loaded or negotiates is reported as a bad library (exit 2), not a crash of
// the certifying process. The probe's output goes to a temporary file, never to --out.
void probe_library(const std::string& exe, const std::string& library) {
  std::string log_name = (fs::temp_directory_path() / "shadowcts-probe-XXXXXX").string();
  const int fd = ::mkstemp(log_name.data());
  if (fd < 0) throw std::runtime_error("cannot create a temporary file for the probe: " + log_name);
  ::close(fd);
  const fs::path log(log_name);
  const InterruptCleanup log_on_interrupt = InterruptCleanup::remove_path(log);
  const double timeout_s = 60;
  const WorkerRun run =
      run_worker({exe, "certify", "--worker", "--probe", "--backend", library}, log, timeout_s);
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  std::error_code ec;
  fs::remove(log, ec);
  std::string message = text.str();
  while (!message.empty() && message.back() == '\n') message.pop_back();
  const std::string field = SHADOWCTS_BACKEND_NEGOTIATE_SYMBOL;
  if (run.end == WorkerRun::End::signalled)
    throw InputError(library, field,
                     "the library crashed while it was loaded or negotiated (signal " +
                         std::to_string(run.code) + ", " + ::strsignal(run.code) + ")");
  if (run.end == WorkerRun::End::timed_out)
    throw InputError(library, field, "loading and negotiation did not finish within 60 s");
  if (run.end == WorkerRun::End::exited && run.code == exit_bad_input) {
    const std::string prefix = "shadowcts: bad input: ";
    const std::size_t at = message.rfind(prefix);
    throw UsageError(at == std::string::npos ? message : message.substr(at + prefix.size()));
  }
  if (run.end != WorkerRun::End::exited || run.code != 0)
    throw InputError(
        library, field,
        "loading it in a worker process failed (" + run_end_text(run, timeout_s) + "): " + message);
}

struct WorkerOutcome {
  WorkerRun run;
  bool judged = false;  // the runner finished and wrote its record
  ordered_json record;  // from the run's results.json
  ordered_json case_summary;
  std::vector<std::string> hashes;
  std::string problem;  // why it was not judged
};

WorkerOutcome run_case_variant(const std::string& exe, const CertifyOptions& options,
                               const std::string& fixture, const std::string& variant,
                               const fs::path& run_dir) {
  WorkerOutcome outcome;
  fs::create_directories(run_dir);
  const fs::path result_file = run_dir / "worker.json";
  std::vector<std::string> args = {exe,
                                   "certify",
                                   "--worker",
                                   "--backend",
                                   fs::absolute(options.library).string(),
                                   "--fixture",
                                   fixture,
                                   "--variant",
                                   variant,
                                   "--out",
                                   (run_dir / "run").string(),
                                   "--worker-result",
                                   result_file.string()};
  if (options.threads) {
    args.push_back("--threads");
    args.push_back(std::to_string(*options.threads));
  }
  outcome.run = run_worker(args, run_dir / "worker.log", options.timeout_s);
  // A worker that died leaves the runner's unfinished folder (run.partial-<pid>): not kept.
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(run_dir, ec))
    if (entry.path().filename().string().rfind("run.partial-", 0) == 0)
      fs::remove_all(entry.path(), ec);
  if (outcome.run.end != WorkerRun::End::exited || outcome.run.code > 1) {
    outcome.problem = run_end_text(outcome.run, options.timeout_s);
    if (outcome.run.end == WorkerRun::End::exited) {
      // The runner's own errors end the worker with a "shadowcts: ..." line. Any other exit
      // status came from code the runner does not control: the library ended the process.
      const std::string line = last_line(run_dir / "worker.log");
      if (line.rfind("shadowcts: ", 0) == 0)
        outcome.problem += ": " + line;
      else
        outcome.problem +=
            " without an error from shadowcts: the library ended the process (exit() in a "
            "plugin call?)" +
            (line.empty() ? std::string(", and printed nothing")
                          : "; worker.log ends with '" + line + "'");
    }
    return outcome;
  }
  try {
    const ordered_json results = read_json(run_dir / "run" / "results.json", "results.json");
    const ordered_json worker = read_json(result_file, "worker result");
    for (const ordered_json& r : results.at("results"))
      if (r.at("variant") == variant) outcome.record = r;
    if (!results.at("cases").empty()) outcome.case_summary = results.at("cases").front();
    outcome.hashes = worker.at("output_sha256").get<std::vector<std::string>>();
    if (outcome.record.is_null()) throw std::runtime_error("no record of the variant");
    outcome.judged = true;
  } catch (const std::exception& e) {
    outcome.problem = std::string("the worker's results cannot be read: ") + e.what();
  }
  return outcome;
}

ordered_json run_json(const WorkerOutcome& o) {
  ordered_json j;
  j["end"] = o.run.end == WorkerRun::End::exited      ? "exited"
             : o.run.end == WorkerRun::End::signalled ? "signal"
             : o.run.end == WorkerRun::End::timed_out ? "timeout"
                                                      : "not started";
  j["code"] = o.run.code;
  j["wall_s"] = std::round(o.run.wall_s * 1000.0) / 1000.0;
  j["judged"] = o.judged;
  if (o.judged) j["verdict"] = o.record.at("verdict");
  j["output_sha256"] = o.hashes.empty() ? std::string() : o.hashes.front();
  if (!o.problem.empty()) j["problem"] = o.problem;
  return j;
}

// The verdict of one case x variant from its two runs.
Entry decide(const std::string& case_name, const std::string& variant, const WorkerOutcome& first,
             const std::optional<WorkerOutcome>& second) {
  Entry e;
  e.case_name = case_name;
  e.variant = variant;
  e.runs.push_back(run_json(first));
  if (second) e.runs.push_back(run_json(*second));
  auto unjudged = [&](const WorkerOutcome& o, const std::string& which) {
    e.verdict = o.run.end == WorkerRun::End::timed_out ? "Timeout" : "Crash";
    e.reason = which + o.problem;
  };
  if (!first.judged) {
    unjudged(first, "");
    return e;
  }
  const ordered_json& r = first.record;
  e.verdict = r.at("verdict").get<std::string>();
  e.reason = r.value("reason", "");
  e.declared_not_supported = e.verdict == "NotSupported" && !r.contains("time_ms");
  if (r.contains("time_ms")) e.time_ms = r.at("time_ms").value("median", 0.0);
  if (r.contains("counters")) e.counters = r.at("counters");
  e.output_sha256 = first.hashes.empty() ? "" : first.hashes.front();
  e.record_name = r.at("name").get<std::string>();
  e.output = r.at("output").get<std::string>();
  e.algorithm = r.at("algorithm").get<std::string>();
  e.backend = r.at("backend").get<std::string>();
  // Every call within one worker must give the same outputs (the runner also fails a repeat
  // that differs from the warm-up run).
  for (std::size_t k = 1; k < first.hashes.size(); ++k)
    if (first.hashes[k] != first.hashes[0] && e.verdict != "Crash") {
      e.verdict = "Fail";
      e.reason = "nondeterministic: call " + std::to_string(k + 1) +
                 " in the same process gave other outputs than the first";
    }
  if (!second) return e;
  if (!second->judged) {
    unjudged(*second, "on the rerun: ");
    return e;
  }
  const std::string again = second->hashes.empty() ? "" : second->hashes.front();
  if (again != e.output_sha256) {
    e.verdict = "Fail";
    e.reason = "nondeterministic: the rerun in a separate process gave other outputs (sha256 " +
               e.output_sha256.substr(0, 16) + "... then " + again.substr(0, 16) + "...)";
  }
  return e;
}

// ---------------------------------------------------------------------------------------------
// The output folder: staged beside it, moved into place when complete.

const std::set<std::string>& certification_names() {
  static const std::set<std::string> names = {"results.json",     "junit.xml", "report.html",
                                              "certificate.json", "cases",     "reproducers"};
  return names;
}

fs::path checked_certification_dir(const std::string& text) {
  if (text.empty()) throw UsageError("--out '': give a folder for the certification");
  fs::path dir = fs::absolute(fs::path(text)).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  const fs::path rel = here.lexically_relative(dir);
  if (dir == dir.root_path() || (!rel.empty() && *rel.begin() != ".."))
    throw UsageError("--out " + text +
                     ": give a folder of its own, not the current folder or one above it");
  if (!fs::exists(dir, ec)) return dir;
  if (!fs::is_directory(dir, ec))
    throw UsageError("--out " + text + ": exists and is not a folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
    if (!certification_names().count(entry.path().filename().string()))
      throw UsageError("--out " + text + ": the folder holds '" + entry.path().filename().string() +
                       "', which is not part of a certification; give an empty or new folder");
  return dir;
}

class Staging {
 public:
  explicit Staging(fs::path target) : target_(std::move(target)) {
    const std::string pid = std::to_string(::getpid());
    dir_ = target_.parent_path() / (target_.filename().string() + ".partial-" + pid);
    unfinished_ = InterruptCleanup::remove_path(dir_);
    std::error_code ec;
    fs::remove_all(dir_, ec);
    fs::create_directories(dir_ / "cases", ec);
    if (ec) throw OutputError(dir_.string(), "cannot create folder: " + ec.message());
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  ~Staging() {
    std::error_code ignored;
    if (!committed_) fs::remove_all(dir_, ignored);
  }
  const fs::path& dir() const { return dir_; }
  void commit() {
    std::error_code ec;
    const fs::path old = target_.parent_path() /
                         (target_.filename().string() + ".old-" + std::to_string(::getpid()));
    const bool had = fs::exists(target_, ec);
    if (had) {
      fs::rename(target_, old, ec);
      if (ec)
        throw OutputError(target_.string(), "cannot move the previous one aside: " + ec.message());
    }
    fs::rename(dir_, target_, ec);
    if (ec)
      throw OutputError(target_.string(),
                        "cannot move the certification into place: " + ec.message());
    committed_ = true;
    if (had) fs::remove_all(old, ec);
  }

 private:
  fs::path target_, dir_;
  bool committed_ = false;
  std::optional<InterruptCleanup> unfinished_;
};

// Image paths in a run's case summary (keys ending in "image" or "images", as the report reads
// them) are relative to that run's folder: make them relative to the certification folder.
void prefix_image_paths(ordered_json& j, const fs::path& folder) {
  auto ends_with = [](const std::string& text, const std::string& end) {
    return text.size() >= end.size() &&
           text.compare(text.size() - end.size(), end.size(), end) == 0;
  };
  if (!j.is_object()) return;
  for (auto& [key, value] : j.items()) {
    if (ends_with(key, "image") && value.is_string())
      value = (folder / value.get<std::string>()).string();
    else if (ends_with(key, "images") && value.is_array())
      for (auto& path : value)
        if (path.is_string()) path = (folder / path.get<std::string>()).string();
    prefix_image_paths(value, folder);
  }
}

// results.json, junit.xml and report.html of the whole certification, from the first runs'
// folders; records of runs that died (Crash, Timeout) and of reruns that differed are added or
// overridden here.
void write_run_outputs(const fs::path& dir, const std::vector<Entry>& entries,
                       const std::string& library, const ordered_json& reproducers) {
  ordered_json root;
  root["schema"] = "shadowcts.results/2";
  const MachineInfo machine = machine_info();
  root["machine"] = {{"cpu", machine.cpu},
                     {"hardware_threads", machine.hardware_threads},
                     {"isa", machine.isa},
                     {"isa_targets", machine.isa_targets}};
  root["threads"] = 0;
  root["timing"] = "shadowcts certify: each record from its case's first worker process";
  root["cases"] = ordered_json::array();
  root["results"] = ordered_json::array();
  std::set<std::string> cases_seen;
  std::vector<RunRecord> junit;
  for (const Entry& e : entries) {
    ordered_json record;
    ordered_json case_summary;
    if (!e.folder.empty()) {
      const ordered_json results = read_json(dir / e.folder / "results.json", "results.json");
      for (const ordered_json& r : results.at("results"))
        if (r.at("variant") == e.variant) record = r;
      if (!results.at("cases").empty()) case_summary = results.at("cases").front();
      prefix_image_paths(case_summary, e.folder);
    }
    if (case_summary.is_null())
      case_summary = {{"name", e.case_name},
                      {"source", "fixture " + e.case_name},
                      {"light", "none"},
                      {"triangles", 0},
                      {"ranged_lights", 0},
                      {"resolution", {0, 0}},
                      {"samples",
                       {{"from", "not run: the worker did not finish"},
                        {"regular", 0},
                        {"sky", 0},
                        {"back_facing", 0}}},
                      {"oracles", ordered_json::object()},
                      {"left_out", ordered_json::array()}};
    if (cases_seen.insert(e.case_name).second) root["cases"].push_back(case_summary);
    std::string reproduce = "shadowcts certify --backend " + quoted(library) + " --fixture " +
                            e.case_name + " --out DIR";
    // A fuzz case's reproducer, and how it was obtained, in results.json and JUnit too.
    for (const ordered_json& r : reproducers)
      if (r.value("case", "") == e.case_name && r.value("variant", "") == e.variant)
        reproduce += "; reproducer: " + r.value("manifest", "") + " (" +
                     r.value("how", r.value("note", "")) + ")";
    if (record.is_null()) {
      record["name"] =
          e.record_name.empty() ? "plugin." + e.variant + "." + e.case_name : e.record_name;
      record["case"] = e.case_name;
      record["output"] = e.output.empty() ? "hard" : e.output;
      record["algorithm"] = e.algorithm.empty() ? "plugin" : e.algorithm;
      record["variant"] = e.variant;
      record["backend"] = e.backend.empty() ? "plugin" : e.backend;
    } else {
      for (auto& image : record["images"])
        image = (fs::path(e.folder) / image.get<std::string>()).string();
    }
    const std::string& verdict = e.verdict;
    // The worker's known limit explains its own verdict, not one the rerun changed.
    if (record.value("verdict", "") != verdict || record.value("reason", "") != e.reason)
      record.erase("known_limit");
    record["verdict"] = verdict;
    record["reason"] = e.reason;
    record["reproduce"] = reproduce;
    root["results"].push_back(record);

    RunRecord r;
    r.case_name = e.case_name;
    r.test_name = record.at("name").get<std::string>();
    r.verdict = verdict_from_name(verdict).value_or(Verdict::crash);
    r.reason = record.at("reason").get<std::string>();
    r.known_limit = record.value("known_limit", "");
    r.reproduce = reproduce;
    r.median_ms = e.time_ms;
    junit.push_back(std::move(r));
  }
  write_file_atomically(dir / "results.json", root.dump(2) + "\n");
  write_junit_xml(dir / "junit.xml", junit);
  write_html_report({dir}, dir / "report.html");
}

ordered_json library_json(const PluginBackend& backend, const std::string& path) {
  ordered_json j;
  j["path"] = fs::absolute(path).lexically_normal().string();
  j["file"] = fs::path(path).filename().string();
  j["sha256"] = sha256_file(path);
  j["name"] = backend.name();
  j["version"] = backend.version();
  j["build_id"] = backend.build_id();
  j["abi_version"] = SHADOWCTS_BACKEND_ABI_VERSION;
  j["variants"] = ordered_json::array();
  for (const PluginVariantInfo& v : backend.variants())
    j["variants"].push_back({{"name", v.name},
                             {"algorithm", v.algorithm},
                             {"output", output_kind_name(v.output)},
                             {"light_kinds", v.light_kinds},
                             {"flags", v.flags},
                             {"max_triangles", v.max_triangles},
                             {"max_regular_samples", v.max_regular_samples},
                             {"max_sample_triangle_pairs", v.max_sample_triangle_pairs},
                             {"soft_error_per_sample", v.soft_error_per_sample},
                             {"soft_error_mean", v.soft_error_mean}});
  return j;
}

ordered_json machine_json() {
  const MachineInfo m = machine_info();
  ordered_json j = {{"cpu", m.cpu},
                    {"hardware_threads", m.hardware_threads},
                    {"isa", m.isa},
                    {"isa_targets", m.isa_targets}};
  struct utsname u {};
  if (::uname(&u) == 0) {
    j["os"] = std::string(u.sysname) + " " + u.release;
    j["arch"] = u.machine;
  }
  return j;
}

// The case list of a certificate: names and input hashes, and the hash of the whole list.
ordered_json case_list_json(const std::vector<std::string>& names, std::string& list_sha256) {
  ordered_json cases = ordered_json::array();
  std::string bytes = "shadowcts.case-list/1\n";
  for (const std::string& name : names) {
    const std::string input = fixture_input_sha256(name);
    cases.push_back({{"name", name}, {"input_sha256", input}});
    bytes += name + " " + input + "\n";
  }
  list_sha256 = sha256_hex(bytes);
  return cases;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

void seal(ordered_json& certificate) {
  certificate.erase("certificate_sha256");
  certificate["certificate_sha256"] = certificate_content_sha256(certificate);
}

void print_entry(std::ostream& out, const Entry& e) {
  out << "  " << std::left << std::setw(13) << e.verdict << std::setw(28) << e.case_name << " "
      << std::setw(16) << e.variant << std::right << std::fixed << std::setprecision(2)
      << std::setw(10) << e.time_ms << " ms  " << std::defaultfloat << e.reason << "\n"
      << std::flush;
}

// `certify --worker --reproduce`: the fuzz case rebuilt from its name, checked in this process
// against the conformance property (runner/conformance_violation.h) and, while the violation
// stays, shrunk (runner/case_shrinking.h); the reproducer (runner/case_reproducer.h) goes to
// out_dir, what it is to result_file. A failure that does not show in one process (a rerun that
// differed) is written unshrunk.
int write_fuzz_reproducer(const PluginBackend& backend, std::size_t index,
                          const CertifyWorkerOptions& w) {
  fuzzing::GeneratedCase generated = fuzzing::make_fuzz_case(w.fixture);
  fuzzing::SampleCase& original = generated.sample_case;
  if (w.threads) original.c.parameters.threads = *w.threads;
  const auto algorithm = backend.algorithm(index);
  const std::optional<Violation> violation = violation_on(*algorithm, w.variant, original);
  std::size_t candidates = 0;
  const fuzzing::SampleCase minimal =
      violation ? shrink_case(original, violation->sample,
                              [&](const fuzzing::SampleCase& candidate) {
                                ++candidates;
                                return violation_on(*algorithm, w.variant, candidate).has_value();
                              })
                : original;
  write_reproducer(w.out_dir, minimal.c, minimal.samples);
  ordered_json result;
  result["shrunk"] = violation.has_value();
  result["violation"] = violation ? violation->what : std::string();
  if (!violation)
    result["note"] =
        "not shrunk: the variant keeps the conformance property on this case within "
        "one process";
  else
    result["how"] = "shrunk from " + std::to_string(original.c.triangles.size()) + " triangles / " +
                    std::to_string(original.samples.samples.size()) + " samples to " +
                    std::to_string(minimal.c.triangles.size()) + " triangles / " +
                    std::to_string(minimal.samples.samples.size()) + " samples in one worker " +
                    "process (" + std::to_string(candidates) +
                    " candidates through the port there)";
  result["worker_runs"] = 1;
  result["triangles"] = minimal.c.triangles.size();
  result["samples"] = minimal.samples.samples.size();
  result["original_triangles"] = original.c.triangles.size();
  result["original_samples"] = original.samples.samples.size();
  write_file_atomically(w.result_file, result.dump(2) + "\n");
  return exit_pass;
}

// Whether a worker's end is one that shrinking per process can look for again: killed by a
// signal, killed at the timeout, or an exit status that is not one of the tool's own (0 to 3:
// pass, conformance failure, bad input, internal error).
bool shrinkable_end(const WorkerRun& run) {
  return run.end == WorkerRun::End::signalled || run.end == WorkerRun::End::timed_out ||
         (run.end == WorkerRun::End::exited && run.code > exit_internal_error);
}

bool same_end(const WorkerRun& a, const WorkerRun& b) {
  return a.end == b.end && (a.end == WorkerRun::End::timed_out || a.code == b.code);
}

// Seconds for messages, to the millisecond.
std::string seconds_text(double s) {
  std::ostringstream text;
  text << std::round(s * 1000.0) / 1000.0;
  return text.str();
}

// The reproducer of a fuzz case x variant whose worker died or hung (`died`: that worker's end, a
// shrinkable_end): the parent writes each candidate as a reproducer folder
// (runner/case_reproducer.h) and runs it in a worker process of its own (`certify --worker --case`,
// no images), keeping a candidate when its worker ends the same way (the same signal, a timeout,
// the same exit status). The whole case is run first (it must end that way from its reproducer
// too), then shrink_case_in_chunks. The budget (options.shrink_runs worker runs,
// options.shrink_seconds seconds, each run at most options.shrink_timeout_s or timeout_s and never
// past the budget) ends it early: the smallest candidate that ended the same way is the reproducer.
// Every run is a line of shrink.log.
ordered_json shrink_in_workers(const std::string& exe, const CertifyOptions& options,
                               const fs::path& case_dir, const fs::path& reproducer_dir,
                               const Entry& e, const WorkerRun& died) {
  const fuzzing::GeneratedCase generated = fuzzing::make_fuzz_case(e.case_name);
  const fuzzing::SampleCase& original = generated.sample_case;
  const double candidate_timeout = options.shrink_timeout_s.value_or(options.timeout_s);
  const fs::path work = case_dir / "shrink";
  std::ofstream log(case_dir / "shrink.log");
  log << "shrinking " << e.case_name << " x " << e.variant
      << ": the worker ended: " << run_end_text(died, options.timeout_s)
      << "; each candidate in a worker of its own "
      << "(timeout " << candidate_timeout << " s), budget " << options.shrink_runs
      << " worker runs and " << options.shrink_seconds << " s\n";
  const auto start = Clock::now();
  std::size_t runs = 0;
  bool exhausted = false;
  std::optional<WorkerRun> whole_case_run;
  auto test = [&](const fuzzing::SampleCase& candidate) {
    const double used = std::chrono::duration<double>(Clock::now() - start).count();
    const double left = options.shrink_seconds - used;
    if (runs >= options.shrink_runs || left <= 0) {
      exhausted = true;
      return CandidateResult::stop;
    }
    std::error_code ec;
    fs::remove_all(work, ec);
    const std::string manifest =
        write_reproducer((work / "candidate").string(), candidate.c, candidate.samples);
    std::vector<std::string> args = {exe,
                                     "certify",
                                     "--worker",
                                     "--backend",
                                     fs::absolute(options.library).string(),
                                     "--case",
                                     manifest,
                                     "--variant",
                                     e.variant,
                                     "--out",
                                     (work / "run").string(),
                                     "--worker-result",
                                     (work / "worker.json").string(),
                                     "--no-images"};
    if (options.threads) {
      args.push_back("--threads");
      args.push_back(std::to_string(*options.threads));
    }
    const double limit = std::min(candidate_timeout, std::round(left * 1000.0) / 1000.0);
    const WorkerRun run = run_worker(args, work / "worker.log", limit);
    ++runs;
    if (!whole_case_run) whole_case_run = run;
    fs::remove_all(work, ec);
    log << "run " << runs << ": " << candidate.c.triangles.size() << " triangles, "
        << candidate.samples.samples.size() << " samples: " << run_end_text(run, limit) << " ("
        << std::round(run.wall_s * 100.0) / 100.0 << " s)";
    if (run.end == WorkerRun::End::timed_out && limit < candidate_timeout) {
      // Cut short by the budget, not by the candidate timeout: its answer is unknown.
      log << " (cut short by the budget: its answer is not used)\n";
      exhausted = true;
      return CandidateResult::stop;
    }
    const bool kept = same_end(run, died);
    log << (kept ? ": kept" : "") << "\n";
    return kept ? CandidateResult::fails : CandidateResult::passes;
  };
  ordered_json what;
  what["shrunk"] = false;
  fuzzing::SampleCase minimal = original;
  const std::string end_text = run_end_text(died, candidate_timeout);
  if (const CandidateResult whole = test(original); whole == CandidateResult::stop) {
    what["note"] = "unshrunk: budget exhausted before the whole case could be run again";
  } else if (whole == CandidateResult::passes) {
    what["note"] = "not shrunk: the whole case, run again from its reproducer in a fresh worker, " +
                   run_end_text(*whole_case_run, candidate_timeout) +
                   " (the first time: " + run_end_text(died, options.timeout_s) + ")";
  } else {
    const ChunkShrinking shrunk = shrink_case_in_chunks(original, test);
    minimal = shrunk.best;
    const bool smaller = minimal.c.triangles.size() < original.c.triangles.size() ||
                         minimal.samples.samples.size() < original.samples.samples.size();
    auto sizes = [](const fuzzing::SampleCase& k) {
      return std::to_string(k.c.triangles.size()) + " triangles / " +
             std::to_string(k.samples.samples.size()) + " samples";
    };
    if (!smaller && exhausted)
      what["note"] = "unshrunk: budget exhausted after " + std::to_string(runs) + " worker runs";
    else if (!smaller)
      what["note"] = "not shrunk: no smaller candidate ended the same way (" + end_text + ")";
    else
      what["how"] = std::string(exhausted ? "partly shrunk (budget exhausted)" : "shrunk") +
                    " from " + sizes(original) + " to " + sizes(minimal) + " in " +
                    std::to_string(runs) + " worker runs, one per candidate (timeout " +
                    seconds_text(candidate_timeout) + " s)";
    what["shrunk"] = smaller;
  }
  log << (what.contains("how") ? what["how"] : what["note"]).get<std::string>() << "\n";
  write_reproducer(reproducer_dir.string(), minimal.c, minimal.samples);
  what["violation"] = run_end_text(died, options.timeout_s);
  what["worker_runs"] = runs;
  what["budget_exhausted"] = exhausted;
  what["candidate_timeout_s"] = candidate_timeout;
  what["triangles"] = minimal.c.triangles.size();
  what["samples"] = minimal.samples.samples.size();
  what["original_triangles"] = original.c.triangles.size();
  what["original_samples"] = original.samples.samples.size();
  return what;
}

// The reproducer of a fuzz case x variant that did not pass (Fail, Crash, Timeout). A run that
// was judged (a Fail, or a Crash the port reported by an error status) is shrunk by one worker
// process (the port runs there, never in this process): `certify --worker --reproduce`; when that
// worker dies or hangs, the whole case is written unshrunk here. A run whose worker died or hung
// (`died`, when shrinkable_end) is shrunk by shrink_in_workers, a worker process per candidate;
// one that exited with one of the tool's own statuses goes the first way.
ordered_json fuzz_reproducer(const std::string& exe, const CertifyOptions& options,
                             const fs::path& staging_dir, const fs::path& case_dir, const Entry& e,
                             const WorkerRun* died) {
  const fs::path rel = fs::path("reproducers") / folder_name(e.case_name) / folder_name(e.variant);
  const fs::path dir = staging_dir / rel;
  ordered_json j;
  j["case"] = e.case_name;
  j["variant"] = e.variant;
  j["verdict"] = e.verdict;
  if (died && shrinkable_end(*died)) {
    const ordered_json what =
        shrink_in_workers(exe, options, staging_dir / case_dir, dir, e, *died);
    for (const auto& [key, value] : what.items()) j[key] = value;
    j["folder"] = rel.string();
    j["manifest"] = (rel / "case.json").string();
    return j;
  }
  const fs::path result_file = staging_dir / case_dir / "reproducer.json";
  std::vector<std::string> args = {exe,
                                   "certify",
                                   "--worker",
                                   "--reproduce",
                                   "--backend",
                                   fs::absolute(options.library).string(),
                                   "--fixture",
                                   e.case_name,
                                   "--variant",
                                   e.variant,
                                   "--out",
                                   dir.string(),
                                   "--worker-result",
                                   result_file.string()};
  if (options.threads) {
    args.push_back("--threads");
    args.push_back(std::to_string(*options.threads));
  }
  const WorkerRun run =
      run_worker(args, staging_dir / case_dir / "reproduce.log", options.timeout_s);
  ordered_json what;
  std::error_code ec;
  if (run.end == WorkerRun::End::exited && run.code == 0 && fs::exists(result_file, ec))
    what = read_json(result_file, "reproducer result");
  if (what.is_null()) {
    fs::remove_all(dir, ec);
    const fuzzing::GeneratedCase generated = fuzzing::make_fuzz_case(e.case_name);
    const fuzzing::SampleCase& whole = generated.sample_case;
    write_reproducer(dir.string(), whole.c, whole.samples);
    what["shrunk"] = false;
    what["violation"] = "";
    what["note"] = "not shrunk: " + run_end_text(run, options.timeout_s) + " while shrinking";
    what["worker_runs"] = 1;
    what["triangles"] = whole.c.triangles.size();
    what["samples"] = whole.samples.samples.size();
    what["original_triangles"] = whole.c.triangles.size();
    what["original_samples"] = whole.samples.samples.size();
  }
  for (auto& [key, value] : what.items()) j[key] = value;
  j["folder"] = rel.string();
  j["manifest"] = (rel / "case.json").string();
  return j;
}

void print_reproducer(std::ostream& out, const std::string& out_dir, const ordered_json& r) {
  out << "    reproducer: " << (fs::path(out_dir) / r.at("manifest").get<std::string>()).string()
      << " (" << r.at("triangles").get<std::size_t>() << " triangles, "
      << r.at("samples").get<std::size_t>() << " samples"
      << (r.at("shrunk").get<bool>() && r.contains("how") ? "; " + r.at("how").get<std::string>()
          : r.at("shrunk").get<bool>()
              ? ", shrunk from " + std::to_string(r.at("original_triangles").get<std::size_t>()) +
                    " triangles and " +
                    std::to_string(r.at("original_samples").get<std::size_t>()) + " samples"
              : "; " + r.value("note", std::string()))
      << ")\n"
      << std::flush;
}

// A fuzz case where the exact oracle calls every sample ambiguous, or that has no sample to
// compare (all back-facing), judges nothing: its generator made it so, not the port (the oracle
// decides it, never the port's answers). Allowed like a declared NotSupported; the reason says it.
bool fuzz_case_with_nothing_to_judge(const Entry& e) {
  return e.verdict == "NotSupported" && fuzzing::is_fuzz_case_name(e.case_name) &&
         e.reason.rfind("no robust sample to judge", 0) == 0;
}

bool allowed(const Entry& e) {
  return e.verdict == "Pass" || (e.verdict == "NotSupported" && e.declared_not_supported) ||
         fuzz_case_with_nothing_to_judge(e);
}

}  // namespace

// -----------------------------------------------------------------------------------------------

std::string suite_version() {
#ifdef SHADOWCTS_GIT_DESCRIBE
  return SHADOWCTS_GIT_DESCRIBE;
#else
  return "unknown";
#endif
}

static std::string suite_sha() {
#ifdef SHADOWCTS_GIT_SHA
  return SHADOWCTS_GIT_SHA;
#else
  return "unknown";
#endif
}

std::vector<std::string> profile_cases(const std::string& profile, const FuzzSelection& fuzz) {
  if (profile == "conformance") return default_fixtures();
  if (profile == "stiff") return stiff_fixtures();
  if (profile == "fuzz") return fuzzing::fuzz_case_names(fuzz.seed, fuzz.count);
  if (profile == "all") {
    std::vector<std::string> all = default_fixtures();
    for (const std::string& s : stiff_fixtures()) all.push_back(s);
    for (const std::string& s : fuzzing::fuzz_case_names(fuzz.seed, fuzz.count)) all.push_back(s);
    return all;
  }
  throw UsageError("--profile " + profile +
                   ": unknown profile (known: conformance, stiff, fuzz, all)");
}

std::string case_input_sha256(const Case& c, const ViewSamples* given_samples) {
  std::string b = "shadowcts.case-input/1\n";
  put_text(b, c.name);
  put_u64(b, c.meshes.size());
  for (const Mesh& m : c.meshes) {
    put_text(b, m.name);
    b += char(m.closed);
    b += char(m.caster);
  }
  put_u64(b, c.triangles.size());
  for (const Triangle& t : c.triangles) {
    put_vec3(b, t.v0);
    put_vec3(b, t.v1);
    put_vec3(b, t.v2);
    put_u32(b, t.mesh);
  }
  b += char(c.light ? 1 + int(c.light->kind) : 0);
  if (c.light) {
    put_vec3(b, c.light->position);
    put_vec3(b, c.light->direction);
    put_float(b, c.light->angular_radius);
  }
  put_u64(b, c.ranged_lights.size());
  for (const RangedLight& l : c.ranged_lights) {
    b += char(l.kind);
    put_vec3(b, l.centre);
    put_float(b, l.range);
    put_vec3(b, l.direction);
    put_float(b, l.cone_half_angle);
  }
  put_vec3(b, c.camera.position);
  put_vec3(b, c.camera.target);
  put_vec3(b, c.camera.up);
  put_float(b, c.camera.vertical_fov_degrees);
  put_float(b, c.camera.near_plane);
  put_float(b, c.camera.far_plane);
  put_u32(b, c.camera.width);
  put_u32(b, c.camera.height);
  put_double(b, c.parameters.eps_rel);
  put_u64(b, c.parameters.seed);
  put_text(b, c.gbuffer_path);
  // Only cases that place their samples themselves hash them (the hashes of the other fixtures
  // stay what they were).
  if (given_samples) {
    b += "samples";
    put_u32(b, given_samples->width);
    put_u32(b, given_samples->height);
    for (const ViewSample& s : given_samples->samples) {
      put_vec3(b, s.position);
      put_vec3(b, s.normal);
      put_u32(b, s.receiver);
      put_u32(b, s.pixel_x);
      put_u32(b, s.pixel_y);
      b += char(s.sample_class);
    }
  }
  return sha256_hex(b);
}

std::string fixture_input_sha256(const std::string& name) {
  if (!fuzzing::is_fuzz_case_name(name)) return case_input_sha256(make_fixture(name));
  const fuzzing::GeneratedCase generated = fuzzing::make_fuzz_case(name);
  return case_input_sha256(generated.sample_case.c, &generated.sample_case.samples);
}

std::string certificate_content_sha256(const ordered_json& certificate) {
  ordered_json content = certificate;
  content.erase("certificate_sha256");
  return sha256_hex(content.dump());
}

int certify_worker(const CertifyWorkerOptions& w, std::ostream& out, std::ostream& err) {
  // A worker lives in a process group of its own (the parent kills the group on a timeout), so a
  // Ctrl-C at the terminal does not reach it: it goes when its parent goes.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() == 1) return exit_internal_error;  // the parent is already gone
  const PluginBackend backend(w.library);
  if (w.probe) return exit_pass;  // loaded and validated
  std::size_t index = backend.variants().size();
  for (std::size_t k = 0; k < backend.variants().size(); ++k)
    if (backend.variants()[k].name == w.variant) index = k;
  if (index == backend.variants().size())
    throw UsageError("--variant " + w.variant + ": the library declares no such variant");
  if (w.reproduce) return write_fuzz_reproducer(backend, index, w);
  Registry registry;
  auto algorithm = backend.algorithm(index);
  const PluginAlgorithm* plugin = algorithm.get();
  registry.add(std::move(algorithm));
  RunOptions options;
  if (w.case_file.empty())
    options.fixtures = {w.fixture};
  else
    options.case_files = {w.case_file};
  options.images = w.images;
  options.out_dir = w.out_dir;
  options.repeats = 1;  // a warm-up run and one timed repeat: two calls in this process
  options.threads = w.threads;
  const int code = run_suite(options, registry, out, err);
  ordered_json result;
  result["output_sha256"] = plugin->output_hashes();
  write_file_atomically(w.result_file, result.dump(2) + "\n");
  return code;
}

int certify(const CertifyOptions& options, std::ostream& out, std::ostream& err) {
  // Everything is checked before anything is written: the library, the options, the cases.
  if (options.library.empty()) throw UsageError("certify: give --backend LIBRARY");
  const std::string exe = self_executable();
  probe_library(exe, options.library);
  const PluginBackend backend(options.library);
  if (!(options.timeout_s > 0)) throw UsageError("--timeout: must be positive");
  if (options.fuzz.count == 0) throw UsageError("--fuzz-count: must be at least 1");
  if (options.shrink_timeout_s && !(*options.shrink_timeout_s > 0))
    throw UsageError("--shrink-timeout: must be positive");
  if (!(options.shrink_seconds >= 0)) throw UsageError("--shrink-seconds: must not be negative");
  const std::vector<std::string> all_cases =
      options.fixtures.empty() ? profile_cases(options.profile, options.fuzz) : options.fixtures;
  for (std::size_t i = 0; i < all_cases.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (all_cases[i] == all_cases[j])
        throw UsageError("--fixture " + all_cases[i] + ": given twice");
  std::string list_sha256;
  const ordered_json case_list = case_list_json(all_cases, list_sha256);  // builds every case
  std::vector<std::string> cases;
  for (std::size_t i = 0; i < all_cases.size(); ++i)
    if (i % options.shard_count == options.shard_index) cases.push_back(all_cases[i]);
  if (cases.empty())
    throw UsageError("shard " + std::to_string(options.shard_index) + "/" +
                     std::to_string(options.shard_count) + " holds no case");
  const fs::path target = checked_certification_dir(options.out_dir);
  const ordered_json library = library_json(backend, options.library);

  Staging staging(target);
  out << "certify " << backend.name() << " " << backend.version() << " (" << backend.build_id()
      << ") from " << options.library << ": " << backend.variants().size() << " variant(s), "
      << cases.size() << " case(s)"
      << (options.shard_count > 1 ? " in shard " + std::to_string(options.shard_index) + "/" +
                                        std::to_string(options.shard_count)
                                  : std::string())
      << ", each run twice in worker processes (timeout " << options.timeout_s << " s)\n"
      << std::flush;
  std::vector<Entry> entries;
  ordered_json reproducers = ordered_json::array();
  for (const std::string& fixture : cases)
    for (const PluginVariantInfo& v : backend.variants()) {
      const fs::path rel = fs::path("cases") / folder_name(fixture) / folder_name(v.name);
      const fs::path dir = staging.dir() / rel;
      const WorkerOutcome first = run_case_variant(exe, options, fixture, v.name, dir / "run-1");
      std::optional<WorkerOutcome> second;
      if (first.judged) {
        second = run_case_variant(exe, options, fixture, v.name, dir / "run-2");
        // Only the first run's folder is kept (its record is the one judged); the rerun's
        // outputs are compared by hash.
        std::error_code ec;
        fs::remove_all(dir / "run-2" / "run", ec);
      }
      Entry e = decide(fixture, v.name, first, second);
      if (first.judged) e.folder = (rel / "run-1" / "run").string();
      if (e.record_name.empty()) {
        e.output = output_kind_name(v.output);
        e.algorithm = v.algorithm;
        e.backend = backend.name();
        e.record_name =
            e.output + "." + e.algorithm + "." + v.name + "." + backend.name() + "." + fixture;
      }
      print_entry(out, e);
      if (e.verdict == "Crash" || e.verdict == "Timeout")
        err << "  the worker's output: "
            << (fs::path(options.out_dir) / rel / (first.judged ? "run-2" : "run-1") / "worker.log")
                   .string()
            << "\n";
      if (fuzzing::is_fuzz_case_name(fixture) &&
          (e.verdict == "Fail" || e.verdict == "Crash" || e.verdict == "Timeout")) {
        // The run whose worker died or hung, if that is what the verdict comes from.
        const WorkerRun* died = !first.judged               ? &first.run
                                : second && !second->judged ? &second->run
                                                            : nullptr;
        reproducers.push_back(fuzz_reproducer(exe, options, staging.dir(), rel, e, died));
        print_reproducer(out, options.out_dir, reproducers.back());
      }
      entries.push_back(std::move(e));
    }

  write_run_outputs(staging.dir(), entries, options.library, reproducers);

  ordered_json certificate;
  certificate["schema"] = certificate_schema;
  certificate["suite"] = {{"version", suite_version()},
                          {"sha", suite_sha()},
                          {"abi_version", SHADOWCTS_BACKEND_ABI_VERSION}};
  certificate["created"] = utc_now();
  certificate["command_line"] = joined_command(options.command_line);
  certificate["machine"] = machine_json();
  certificate["library"] = library;
  certificate["profile"] = options.fixtures.empty() ? options.profile : "custom";
  if (options.fixtures.empty() && (options.profile == "fuzz" || options.profile == "all"))
    certificate["fuzz"] = {{"seed", options.fuzz.seed},
                           {"count", options.fuzz.count},
                           {"generators", fuzzing::fuzz_generator_names()}};
  certificate["case_list_sha256"] = list_sha256;
  certificate["cases"] = case_list;
  certificate["shard"] = {{"index", options.shard_index}, {"count", options.shard_count}};
  certificate["timeout_s"] = options.timeout_s;
  certificate["shrink_budget"] = {
      {"runs", options.shrink_runs},
      {"seconds", options.shrink_seconds},
      {"timeout_s", options.shrink_timeout_s.value_or(options.timeout_s)}};
  certificate["results"] = ordered_json::array();
  for (const Entry& e : entries) certificate["results"].push_back(entry_json(e));
  certificate["reproducers"] = reproducers;
  seal(certificate);
  write_file_atomically(staging.dir() / "certificate.json", certificate.dump(2) + "\n");
  staging.commit();

  std::size_t good = 0;
  std::map<std::string, std::size_t> counts;
  for (const Entry& e : entries) {
    ++counts[e.verdict];
    good += allowed(e);
  }
  const bool any_pass = counts.count("Pass") != 0;
  out << "\n" << entries.size() << " case x variant results:";
  for (const auto& [verdict, count] : counts) out << " " << count << " " << verdict;
  out << "\nwrote " << (fs::path(options.out_dir) / "certificate.json").string() << " beside "
      << "report.html, results.json and junit.xml"
      << (reproducers.empty() ? std::string()
                              : ", and " + std::to_string(reproducers.size()) +
                                    " reproducer(s) of failing fuzz cases under " +
                                    (fs::path(options.out_dir) / "reproducers").string())
      << (good != entries.size() ? "; the certification does not pass"
          : !any_pass ? "; nothing was judged (every case NotSupported): it certifies nothing"
                      : "")
      << "\n";
  return good == entries.size() && any_pass ? exit_pass : exit_conformance_failure;
}

int verify_certificate(const std::string& dir, std::ostream& out) {
  const fs::path file = fs::path(dir) / "certificate.json";
  if (!fs::exists(file)) throw UsageError("certify verify " + dir + ": no certificate.json there");
  const ordered_json c = read_json(file, "certificate");
  std::vector<std::string> rejections;
  auto reject = [&](const std::string& why) { rejections.push_back(why); };
  auto str = [&](const ordered_json& j, const char* key) {
    return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
  };
  if (str(c, "schema") != certificate_schema)
    reject("schema is '" + str(c, "schema") + "', not " + certificate_schema);
  const std::string recorded = str(c, "certificate_sha256");
  const std::string computed = certificate_content_sha256(c);
  if (recorded != computed)
    reject("certificate_sha256 does not match the content (" + computed.substr(0, 16) +
           "...): the certificate was edited");
  try {
    const std::string version = c.at("suite").at("version").get<std::string>();
    if (version != suite_version())
      reject("made by suite " + version + ", this is suite " + suite_version() +
             ": verify with the suite that made it");
    // The case list: names from the profile of this suite (or the certificate's own list for a
    // custom selection), each case's inputs rebuilt and hashed again.
    const std::string profile = c.at("profile").get<std::string>();
    std::vector<std::string> names;
    for (const ordered_json& k : c.at("cases")) names.push_back(k.at("name").get<std::string>());
    if (profile != "custom") {
      // The fuzz profile's cases follow from the seed and count the certificate records.
      FuzzSelection fuzz;
      if (profile == "fuzz" || profile == "all") {
        fuzz.seed = c.at("fuzz").at("seed").get<std::uint64_t>();
        fuzz.count = c.at("fuzz").at("count").get<std::uint32_t>();
        if (c.at("fuzz").at("generators") != ordered_json(fuzzing::fuzz_generator_names()))
          reject("the fuzz generators are not this suite's");
      }
      const std::vector<std::string> expected = profile_cases(profile, fuzz);
      if (names != expected)
        reject("the case list is not the " + profile + " profile's " +
               std::to_string(expected.size()) + " cases in order" +
               (profile == "fuzz" || profile == "all"
                    ? " for fuzz seed " + std::to_string(fuzz.seed) + " and count " +
                          std::to_string(fuzz.count)
                    : std::string()));
    } else {
      out << "note: a custom case selection, not a whole profile\n";
    }
    std::string list_sha256;
    const ordered_json rebuilt = case_list_json(names, list_sha256);
    for (std::size_t i = 0; i < names.size(); ++i)
      if (rebuilt[i].at("input_sha256") != c.at("cases")[i].at("input_sha256"))
        reject("case " + names[i] + ": its inputs hash differently here (the fixture changed)");
    if (list_sha256 != c.at("case_list_sha256").get<std::string>())
      reject("case_list_sha256 does not match the case list");
    // The library, where it still is.
    const ordered_json& library = c.at("library");
    const std::string path = library.at("path").get<std::string>();
    if (fs::exists(path)) {
      if (sha256_file(path) != library.at("sha256").get<std::string>())
        reject("the library at " + path + " is not the one certified (its SHA-256 differs)");
    } else {
      out << "note: the library " << path << " is not here: its SHA-256 is not rechecked\n";
    }
    std::vector<std::string> variants;
    for (const ordered_json& v : library.at("variants"))
      variants.push_back(v.at("name").get<std::string>());
    // Completeness: every case x variant exactly once, nothing else; allowed statuses only.
    std::map<std::pair<std::string, std::string>, int> seen;
    for (const ordered_json& r : c.at("results")) {
      const Entry e = entry_from_json(r);
      const auto key = std::pair(e.case_name, e.variant);
      if (++seen[key] == 2)
        reject("case " + e.case_name + " variant " + e.variant + " appears more than once");
      if (std::find(names.begin(), names.end(), e.case_name) == names.end() ||
          std::find(variants.begin(), variants.end(), e.variant) == variants.end())
        reject("result for case " + e.case_name + " variant " + e.variant +
               " that is not in the case list x variants");
      if (!allowed(e))
        reject("case " + e.case_name + " variant " + e.variant + ": " + e.verdict +
               (e.verdict == "NotSupported" ? " (not declared by the capabilities)" : "") +
               (e.reason.empty() ? "" : ": " + e.reason));
      if (e.verdict == "Pass") {
        if (e.runs.size() != 2 || e.runs[0].value("output_sha256", "") != e.output_sha256 ||
            e.runs[1].value("output_sha256", "") != e.output_sha256 || e.output_sha256.empty())
          reject("case " + e.case_name + " variant " + e.variant +
                 ": Pass without two runs of the same output hash");
      }
    }
    std::size_t missing = 0;
    for (const std::string& name : names)
      for (const std::string& v : variants)
        if (!seen.count({name, v})) {
          if (++missing <= 5) reject("case " + name + " variant " + v + " is missing");
        }
    if (std::none_of(c.at("results").begin(), c.at("results").end(),
                     [](const ordered_json& r) { return r.value("verdict", "") == "Pass"; }))
      reject(
          "no case x variant is Pass: every one was NotSupported, the certificate certifies "
          "nothing");
    if (missing > 5)
      reject(std::to_string(missing - 5) + " more case x variant results are missing");
    const ordered_json& shard = c.at("shard");
    if (shard.contains("count") && shard.at("count").get<std::uint32_t>() > 1 && missing > 0)
      reject("this is shard " + std::to_string(shard.at("index").get<std::uint32_t>()) + "/" +
             std::to_string(shard.at("count").get<std::uint32_t>()) +
             ": join the shards with `shadowcts certify merge OUT DIR...` and verify that");
  } catch (const nlohmann::json::exception& e) {
    reject(std::string("malformed certificate: ") + e.what());
  } catch (const InputError& e) {
    reject(e.what());
  }
  if (!rejections.empty()) {
    out << "REJECTED " << file.string() << ":\n";
    for (const std::string& why : rejections) out << "  " << why << "\n";
    return exit_conformance_failure;
  }
  out << "ACCEPTED " << file.string() << ": " << c.at("library").at("name").get<std::string>()
      << " " << c.at("library").at("version").get<std::string>() << ", " << c.at("results").size()
      << " case x variant results, all Pass or NotSupported as allowed\n";
  return exit_pass;
}

int merge_certificates(const std::string& out_dir, const std::vector<std::string>& dirs,
                       std::ostream& out) {
  if (dirs.empty()) throw UsageError("certify merge: give the shard folders");
  std::vector<ordered_json> shards;
  for (const std::string& d : dirs) {
    const fs::path file = fs::path(d) / "certificate.json";
    ordered_json c = read_json(file, "certificate");
    if (c.value("certificate_sha256", "") != certificate_content_sha256(c))
      throw InputError(file.string(), "certificate_sha256",
                       "does not match the content: the shard was edited");
    shards.push_back(std::move(c));
  }
  const ordered_json& first = shards.front();
  const std::uint32_t count = first.at("shard").at("count").get<std::uint32_t>();
  if (count != shards.size())
    throw UsageError("certify merge: the shards say there are " + std::to_string(count) + ", " +
                     std::to_string(shards.size()) + " given");
  std::vector<int> seen(count, 0);
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const ordered_json& s = shards[k];
    const std::string file = (fs::path(dirs[k]) / "certificate.json").string();
    for (const char* key : {"suite", "profile", "case_list_sha256", "timeout_s"})
      if (s.at(key) != first.at(key))
        throw InputError(file, key, "differs from the first shard's: not one certification");
    if (s.at("library").at("sha256") != first.at("library").at("sha256"))
      throw InputError(file, "library.sha256", "differs from the first shard's: another library");
    if (s.at("shard").at("count") != first.at("shard").at("count"))
      throw InputError(file, "shard.count", "differs from the first shard's");
    const std::uint32_t index = s.at("shard").at("index").get<std::uint32_t>();
    if (index >= count || seen[index]++)
      throw InputError(file, "shard.index",
                       std::to_string(index) + " is given twice or out of range");
  }
  const fs::path target = checked_certification_dir(out_dir);
  Staging staging(target);
  // Results in the case list's order, then the library's variant order.
  std::map<std::string, std::size_t> case_order, variant_order;
  for (const ordered_json& k : first.at("cases"))
    case_order.emplace(k.at("name").get<std::string>(), case_order.size());
  for (const ordered_json& v : first.at("library").at("variants"))
    variant_order.emplace(v.at("name").get<std::string>(), variant_order.size());
  std::vector<std::pair<std::pair<std::size_t, std::size_t>, Entry>> ordered;
  std::vector<std::pair<std::size_t, ordered_json>> reproducers;
  ordered_json command_lines = ordered_json::array();
  for (std::size_t k = 0; k < shards.size(); ++k) {
    command_lines.push_back(shards[k].at("command_line"));
    for (const char* folder : {"cases", "reproducers"}) {
      std::error_code ec;
      fs::create_directories(staging.dir() / folder, ec);
      for (const fs::directory_entry& entry :
           fs::directory_iterator(fs::path(dirs[k]) / folder, ec)) {
        const fs::path to = staging.dir() / folder / entry.path().filename();
        if (fs::exists(to)) throw InputError(entry.path().string(), folder, "is in two shards");
        fs::copy(entry.path(), to, fs::copy_options::recursive, ec);
        if (ec) throw OutputError(to.string(), "cannot copy: " + ec.message());
      }
    }
    for (const ordered_json& r : shards[k].value("reproducers", ordered_json::array())) {
      const auto c = case_order.find(r.at("case").get<std::string>());
      reproducers.push_back({c == case_order.end() ? case_order.size() : c->second, r});
    }
    for (const ordered_json& r : shards[k].at("results")) {
      Entry e = entry_from_json(r);
      const auto c = case_order.find(e.case_name);
      const auto v = variant_order.find(e.variant);
      ordered.push_back({{c == case_order.end() ? case_order.size() : c->second,
                          v == variant_order.end() ? variant_order.size() : v->second},
                         std::move(e)});
    }
  }
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Entry> entries;
  for (auto& [key, e] : ordered) entries.push_back(std::move(e));

  ordered_json merged = first;
  merged["created"] = utc_now();
  merged["command_line"] = command_lines;
  merged["shard"] = {{"index", 0}, {"count", 1}, {"merged_from", count}};
  merged["results"] = ordered_json::array();
  for (const Entry& e : entries) merged["results"].push_back(entry_json(e));
  std::stable_sort(reproducers.begin(), reproducers.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  merged["reproducers"] = ordered_json::array();
  for (const auto& [position, r] : reproducers) merged["reproducers"].push_back(r);
  write_run_outputs(staging.dir(), entries, first.at("library").at("path").get<std::string>(),
                    merged["reproducers"]);
  seal(merged);
  write_file_atomically(staging.dir() / "certificate.json", merged.dump(2) + "\n");
  staging.commit();
  out << "merged " << shards.size() << " shards (" << entries.size()
      << " case x variant results) into " << (fs::path(out_dir) / "certificate.json").string()
      << "\n";
  return exit_pass;
}

}  // namespace shadowcts
