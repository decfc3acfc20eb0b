#pragma once
// `shadowcts certify`: certifies a port the suite has never seen, loaded from a shared library
// through the C ABI (include/shadowcts/backend_abi.h). Every case x variant of a profile runs in
// worker processes (a crash is a Crash verdict, a hang a Timeout, and the run goes on), twice, in
// separate processes (different outputs are a Fail); the outputs are judged by the runner like a
// registered algorithm's, and DIR/certificate.json records what was run and what came out, for
// `shadowcts certify verify` to check. docs/certify.md.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

inline constexpr const char* certificate_schema = "shadowcts.certificate/1";

// The fuzz profile's cases: fuzz.<generator>.<seed>.<index> for the watertight, degenerate and
// differential generators and every index below `count` (fixtures/fuzz/fuzz_fixtures.h).
struct FuzzSelection {
  std::uint64_t seed = 1;
  std::uint32_t count = 32;  // per generator
};

struct CertifyOptions {
  std::string library;                  // the port's shared library
  std::string profile = "conformance";  // conformance | stiff | fuzz | all
  FuzzSelection fuzz;                   // for the profiles fuzz and all
  // Instead of a whole profile: these fixtures only (the certificate says "custom"; tests and
  // quick checks).
  std::vector<std::string> fixtures;
  std::string out_dir;
  double timeout_s = 300;  // per worker process (one run of one case x variant)
  // Shrinking a fuzz case that crashed or hung, one worker process per candidate: each candidate
  // may take shrink_timeout_s (unset: timeout_s) and one failing case x variant at most
  // shrink_runs worker runs and shrink_seconds seconds in all (0: no shrinking).
  std::optional<double> shrink_timeout_s;
  std::uint32_t shrink_runs = 100;
  double shrink_seconds = 300;
  std::uint32_t shard_index = 0, shard_count = 1;
  std::optional<std::uint32_t> threads;
  std::vector<std::string> command_line;  // argv, recorded in the certificate
};

// The parent: plans, runs the workers, writes DIR (results.json, junit.xml, report.html, the
// workers' run folders under cases/, certificate.json) completely or not at all. A bad library
// (missing, no entry point, another ABI version, nonsense capabilities, a null function) or bad
// options throw InputError / UsageError before anything is written. Returns 0 when every case x
// variant is Pass or declared NotSupported and at least one is Pass, 1 otherwise.
int certify(const CertifyOptions& options, std::ostream& out, std::ostream& err);

struct CertifyWorkerOptions {
  std::string library, fixture, variant, out_dir, result_file;
  // Instead of `fixture`: a case manifest (a reproducer's case.json, samples in its G-buffer), as
  // the parent writes each candidate when it shrinks a crash or a hang.
  std::string case_file;
  bool images = true;  // false: the run writes no images (shrink candidates)
  std::optional<std::uint32_t> threads;
  bool probe = false;  // only load and validate the library (exit 2 naming the field when bad)
  // Write a reproducer of the fuzz case `fixture` into out_dir instead of running the runner:
  // shrunk while the variant still violates the conformance property in this process.
  bool reproduce = false;
};

// `shadowcts certify --worker --probe`: loads and validates the library only (the parent does this
// first, so that a library that crashes while loading is a bad library, not a crash of certify).
// `shadowcts certify --worker`: one case x variant (a fixture, or a case manifest) through the
// runner into out_dir, then the output hashes of every call into result_file. Returns the
// runner's exit code.
// `shadowcts certify --worker --reproduce`: the minimal reproducer of a failing fuzz case into
// out_dir, what it is into result_file; 0 when written.
int certify_worker(const CertifyWorkerOptions& options, std::ostream& out, std::ostream& err);

// `shadowcts certify verify DIR`: 0 accepted, 1 rejected (each reason printed); throws
// UsageError / InputError when DIR holds no readable certificate.
int verify_certificate(const std::string& dir, std::ostream& out);

// `shadowcts certify merge OUT DIR...`: joins shard certifications into OUT (which verify then
// checks like one certification). Throws UsageError / InputError when the shards do not belong
// together (another suite, library, profile or shard count; a shard twice or missing; an edited
// shard), before anything is written.
int merge_certificates(const std::string& out_dir, const std::vector<std::string>& dirs,
                       std::ostream& out);

// The cases of a profile, in order (`all`: conformance, stiff, then fuzz). Throws UsageError for
// an unknown profile.
std::vector<std::string> profile_cases(const std::string& profile, const FuzzSelection& fuzz = {});

// SHA-256 of what a case gives an algorithm and the oracles (geometry, meshes, lights, camera,
// eps_rel, seed, and the view samples where the case places them itself), in a fixed byte order.
std::string case_input_sha256(const Case& c, const ViewSamples* given_samples = nullptr);

// case_input_sha256 of a fixture by name (a fuzz case with its samples).
std::string fixture_input_sha256(const std::string& name);

// SHA-256 of the certificate's canonical content: the JSON without "certificate_sha256", dumped
// compactly in its key order.
std::string certificate_content_sha256(const nlohmann::ordered_json& certificate);

// The suite's version (git describe at configure time, or the project version).
std::string suite_version();

}  // namespace shadowcts
