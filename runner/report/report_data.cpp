#include "report_data.h"

#include <fstream>
#include <map>
#include <sstream>

#include "run_record.h"
#include "shadowcts/errors.h"
#include "shadowcts/verdict.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

fs::path normal_absolute(const fs::path& p) {
  return fs::absolute(p).lexically_normal();
}

std::string label_of(const fs::path& dir, const fs::path& page_dir) {
  fs::path relative = normal_absolute(dir).lexically_relative(normal_absolute(page_dir));
  if (relative.empty()) return normal_absolute(dir).string();  // no relative path exists
  std::string text = relative.string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

ordered_json read_results(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "file", "cannot be read (is this a result directory?)");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return ordered_json::parse(text.str());
  } catch (const ordered_json::exception& e) {
    // parse_error, and out_of_range for a number beyond double's range ("1e999").
    throw InputError(file.string(), "JSON", e.what());
  }
}

std::string required_string(const ordered_json& object, const char* key, const std::string& source,
                            const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_string())
    throw InputError(source, where, std::string("\"") + key + "\" is missing or not a string");
  return it->get<std::string>();
}

// The times a comparison judges: medians, minima and maxima, where given, are numbers >= 0.
void require_times(const ordered_json& record, const std::string& source,
                   const std::string& where) {
  const auto check = [&](const ordered_json& timing, const std::string& field) {
    if (!timing.is_object()) throw InputError(source, where, field + ": not an object");
    for (const char* key : {"median", "min", "max"}) {
      const auto it = timing.find(key);
      if (it != timing.end() && !(it->is_number() && it->get<double>() >= 0.0))
        throw InputError(source, where, field + "." + key + ": not a number >= 0");
    }
  };
  const auto t = record.find("time_ms");
  if (t == record.end()) return;
  check(*t, "time_ms");
  const auto phases = t->find("phases");
  if (phases == t->end()) return;
  if (!phases->is_object()) throw InputError(source, where, "time_ms.phases: not an object");
  for (auto it = phases->begin(); it != phases->end(); ++it)
    check(it.value(), "time_ms.phases." + it.key());
}

const ordered_json& required_array(const ordered_json& object, const char* key,
                                   const std::string& source) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_array())
    throw InputError(source, "top level", std::string("\"") + key + "\" is missing or not a list");
  return *it;
}

}  // namespace

std::string ReportRecord::label() const {
  return algorithm + ":" + variant + " [" + backend + "]";
}

bool ReportData::has_comparisons() const {
  for (const ReportCase& c : cases)
    for (const ReportRecord& r : c.records)
      if (r.versions.size() > 1) return true;
  return false;
}

std::string ReportData::page_relative(std::size_t dir, const std::string& path_in_dir) const {
  return (normal_absolute(dirs[dir].dir) / path_in_dir)
      .lexically_normal()
      .lexically_relative(normal_absolute(page_dir))
      .string();
}

ReportData load_report_data(const std::vector<fs::path>& result_dirs, const fs::path& page_dir) {
  if (result_dirs.empty()) throw UsageError("report: no result directory given");
  // The same folder twice (or by two paths) would be compared with itself and counted twice.
  for (std::size_t d = 0; d < result_dirs.size(); ++d)
    for (std::size_t e = 0; e < d; ++e) {
      std::error_code ec;
      if (fs::equivalent(result_dirs[d], result_dirs[e], ec))
        throw UsageError("report: " + result_dirs[d].string() + " is given twice" +
                         (result_dirs[d] == result_dirs[e]
                              ? std::string()
                              : " (also as " + result_dirs[e].string() + ")"));
    }
  ReportData data;
  data.page_dir = page_dir;
  std::map<std::string, std::size_t> case_index;
  // (case index, record index) per record name, so records merge across directories.
  std::map<std::string, std::pair<std::size_t, std::size_t>> record_index;
  for (std::size_t d = 0; d < result_dirs.size(); ++d) {
    const fs::path file = result_dirs[d] / "results.json";
    const std::string source = file.string();
    ordered_json root = read_results(file);
    if (!root.is_object()) throw InputError(source, "top level", "not an object");
    const std::string schema = required_string(root, "schema", source, "top level");
    // Version 2 is version 1 with phase times and the Highway ISA added, so older result
    // directories still compare with newer ones; a later version may change meanings.
    if (schema != "shadowcts.results/1" && schema != "shadowcts.results/2")
      throw InputError(source, "schema",
                       "'" + schema + "' is neither shadowcts.results/1 nor shadowcts.results/2");
    const ordered_json& cases = required_array(root, "cases", source);
    const ordered_json& results = required_array(root, "results", source);

    for (const ordered_json& c : cases) {
      const std::string name = required_string(c, "name", source, "cases[]");
      auto [it, inserted] = case_index.try_emplace(name, data.cases.size());
      if (inserted) data.cases.push_back(ReportCase{name, {}, {}});
      ReportCase& target = data.cases[it->second];
      if (!target.summaries.empty() && target.summaries.back().dir == d)
        throw InputError(source, "cases[] " + name, "appears twice");
      target.summaries.push_back(Version{d, c});
    }
    for (const ordered_json& r : results) {
      const std::string name = required_string(r, "name", source, "results[]");
      const std::string where = "results[] " + name;
      const std::string case_name = required_string(r, "case", source, where);
      const auto c = case_index.find(case_name);
      // The case must be listed by this directory, not only by an earlier one.
      if (c == case_index.end() || data.cases[c->second].summaries.back().dir != d)
        throw InputError(source, where, "its case '" + case_name + "' is not in \"cases\"");
      auto [it, inserted] = record_index.try_emplace(
          name, std::pair{c->second, data.cases[c->second].records.size()});
      if (inserted) {
        ReportRecord record;
        record.name = name;
        record.output = required_string(r, "output", source, where);
        if (record.output != output_kind_name(OutputKind::hard_shadow) &&
            record.output != output_kind_name(OutputKind::soft_shadow) &&
            record.output != output_kind_name(OutputKind::light_lists))
          throw InputError(source, where,
                           "\"output\" is '" + record.output + "', not one of hard, soft, lights");
        record.algorithm = required_string(r, "algorithm", source, where);
        record.variant = required_string(r, "variant", source, where);
        record.backend = required_string(r, "backend", source, where);
        data.cases[c->second].records.push_back(std::move(record));
      } else if (it->second.first != c->second) {
        throw InputError(source, where, "belongs to another case in an earlier directory");
      }
      ReportRecord& target = data.cases[it->second.first].records[it->second.second];
      if (!target.versions.empty() && target.versions.back().dir == d)
        throw InputError(source, where, "appears twice");
      const std::string verdict = required_string(r, "verdict", source, where);
      // An unknown verdict would go unranked, and a regression to it unnoticed.
      if (!verdict_from_name(verdict))
        throw InputError(source, where,
                         "\"verdict\" is '" + verdict +
                             "', not one of Pass, Fail, QualityWarning, NotSupported, Crash, "
                             "Timeout");
      require_times(r, source, where);
      target.versions.push_back(Version{d, r});
    }
    root.erase("cases");
    root.erase("results");
    data.dirs.push_back(ResultDirectory{result_dirs[d], label_of(result_dirs[d], page_dir), root});
  }
  return data;
}

}  // namespace shadowcts
