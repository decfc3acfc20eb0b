#pragma once
#include <memory>
#include <string>
#include <vector>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// Holds every algorithm x backend the runner knows. The runner sees algorithms only through it.
class Registry {
 public:
  void add(std::unique_ptr<Algorithm> algorithm);
  const std::vector<std::unique_ptr<Algorithm>>& algorithms() const { return algorithms_; }
  // nullptr when absent.
  const Algorithm* find(const std::string& id, const std::string& backend) const;

 private:
  std::vector<std::unique_ptr<Algorithm>> algorithms_;
};

// The registry with every built-in algorithm and backend of this build.
const Registry& builtin_registry();

}  // namespace shadowcts
