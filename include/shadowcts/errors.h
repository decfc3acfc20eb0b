#pragma once
#include <stdexcept>
#include <string>

namespace shadowcts {

// Bad input: a file, manifest or parameter that does not describe a valid case.
// The message names the file and the element; the tool exits with code 2.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& source, const std::string& element, const std::string& problem)
      : std::runtime_error(source + ": " + element + ": " + problem) {}
};

// Bad command-line usage (also exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output (the output folder, an image, results.json, junit.xml, report.html) cannot be
// written: exit code 3, the message names the file. Kept apart from other exceptions so that a
// full disk is never recorded as an algorithm's Crash.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem) {}
};

}  // namespace shadowcts
