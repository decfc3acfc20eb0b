#pragma once
// The verdict vocabulary of the Vulkan CTS / dEQP, so CI dashboards read it the same way.
#include <optional>
#include <string_view>

namespace shadowcts {

// timeout: a run killed past its time limit (`certify`'s workers); like a crash, a failure.
enum class Verdict { pass, fail, quality_warning, not_supported, crash, timeout };

// The most a statistical verdict may fail a faithful algorithm by chance, per record: a mean
// error over few samples judged against its budget (docs/soft-shadow-budgets.md), an approximate
// map's mismatch rate against its ceiling (docs/specification.md).
inline constexpr double statistical_verdict_failure_probability = 1e-9;

// The run did not finish: no output, no timings.
constexpr bool did_not_finish(Verdict v) {
  return v == Verdict::crash || v == Verdict::timeout;
}

constexpr std::string_view verdict_name(Verdict v) {
  switch (v) {
    case Verdict::pass:
      return "Pass";
    case Verdict::fail:
      return "Fail";
    case Verdict::quality_warning:
      return "QualityWarning";
    case Verdict::not_supported:
      return "NotSupported";
    case Verdict::crash:
      return "Crash";
    case Verdict::timeout:
      return "Timeout";
  }
  return "Crash";
}

// The verdict a name stands for (results.json, JUnit); nullopt for anything else.
constexpr std::optional<Verdict> verdict_from_name(std::string_view name) {
  for (Verdict v : {Verdict::pass, Verdict::fail, Verdict::quality_warning, Verdict::not_supported,
                    Verdict::crash, Verdict::timeout})
    if (verdict_name(v) == name) return v;
  return std::nullopt;
}

}  // namespace shadowcts
