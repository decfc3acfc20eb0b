#pragma once
// The verdict vocabulary of the Vulkan CTS / dEQP, so CI dashboards read it the same way.
#include <string_view>

namespace shadowcts {

enum class Verdict { pass, fail, quality_warning, not_supported, crash };

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
  }
  return "Crash";
}

}  // namespace shadowcts
