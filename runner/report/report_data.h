#pragma once
// The report's model: one or several result directories (results.json each), merged by case and
// record name. Disjoint directories (shards of one run) merge into their union; a record present
// in several directories keeps one version per directory, for a before/after comparison.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowcts {

struct ResultDirectory {
  std::filesystem::path dir;
  std::string label;           // how the page names it: the path relative to the page
  nlohmann::ordered_json run;  // results.json without "cases" and "results"
};

// One directory's copy of a case summary or of a record.
struct Version {
  std::size_t dir = 0;  // index into ReportData::dirs
  nlohmann::ordered_json json;
};

struct ReportRecord {
  std::string name;  // dotted, e.g. hard.bruteforce.exact.reference.gate_house.20k
  std::string output, algorithm, variant, backend;
  std::vector<Version> versions;  // in directory order, at most one per directory

  std::string label() const;  // "algorithm:variant [backend]"
};

struct ReportCase {
  std::string name;
  std::vector<Version> summaries;  // the case's entry of "cases", per directory that has it
  std::vector<ReportRecord> records;
};

struct ReportData {
  std::filesystem::path page_dir;  // where the page lies; image paths are relative to it
  std::vector<ResultDirectory> dirs;
  std::vector<ReportCase> cases;  // in order of first appearance, directory by directory

  // True when some record appears in more than one directory.
  bool has_comparisons() const;

  // A path that results.json of directory `dir` gives relative to itself, relative to the page.
  std::string page_relative(std::size_t dir, const std::string& path_in_dir) const;
};

// Reads DIR/results.json for every directory. Labels are relative to page_dir, the folder the
// page is written to. Throws InputError when a file is missing, is not JSON, or lacks the fields
// the report needs.
ReportData load_report_data(const std::vector<std::filesystem::path>& result_dirs,
                            const std::filesystem::path& page_dir);

}  // namespace shadowcts
