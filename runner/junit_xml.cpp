#include "junit_xml.h"

#include <cstdio>
#include <map>
#include <sstream>

#include "atomic_file.h"
#include "report/html_text.h"

namespace shadowcts {
namespace {

std::string seconds(double ms) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6f", ms / 1000.0);
  return buffer;
}

}  // namespace

void write_junit_xml(const std::filesystem::path& path, const std::vector<RunRecord>& records) {
  // Suites in order of first appearance, so the file follows the run.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const RunRecord*>> suites;
  for (const RunRecord& r : records) {
    if (!suites.count(r.case_name)) order.push_back(r.case_name);
    suites[r.case_name].push_back(&r);
  }
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"shadowcts\">\n";
  for (const std::string& name : order) {
    const auto& members = suites[name];
    int failures = 0, errors = 0, skipped = 0;
    double total_ms = 0;
    for (const RunRecord* r : members) {
      failures += r->verdict == Verdict::fail;
      errors += did_not_finish(r->verdict);
      skipped += r->verdict == Verdict::not_supported;
      total_ms += r->median_ms;
    }
    xml << "  <testsuite name=\"" << html_escape(name) << "\" tests=\"" << members.size()
        << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" skipped=\"" << skipped
        << "\" time=\"" << seconds(total_ms) << "\">\n";
    for (const RunRecord* r : members) {
      xml << "    <testcase classname=\"" << html_escape(name) << "\" name=\""
          << html_escape(r->test_name) << "\" time=\"" << seconds(r->median_ms) << "\">";
      // Failures carry the command that reruns just this record.
      const std::string reason = html_escape(
          r->reason + (r->known_limit.empty() ? "" : " (a known limit: " + r->known_limit + ")") +
          " (reproduce: " + r->reproduce + ")");
      switch (r->verdict) {
        case Verdict::fail:
          xml << "<failure message=\"" << reason << "\" type=\"Fail\"/>";
          break;
        case Verdict::crash:
          xml << "<error message=\"" << reason << "\" type=\"Crash\"/>";
          break;
        case Verdict::timeout:
          xml << "<error message=\"" << reason << "\" type=\"Timeout\"/>";
          break;
        case Verdict::not_supported:
          xml << "<skipped message=\"NotSupported: " << reason << "\"/>";
          break;
        case Verdict::quality_warning:
          xml << "<system-out>QualityWarning: " << reason << "</system-out>";
          break;
        case Verdict::pass:
          break;
      }
      xml << "</testcase>\n";
    }
    xml << "  </testsuite>\n";
  }
  xml << "</testsuites>\n";
  write_file_atomically(path, xml.str());
}

}  // namespace shadowcts
