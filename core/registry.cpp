#include "shadowcts/registry.h"

#include <stdexcept>

namespace shadowcts {

void Registry::add(std::unique_ptr<Algorithm> algorithm) {
  const AlgorithmInfo& meta = algorithm->info();
  if (meta.variants.empty())
    throw std::logic_error("algorithm " + meta.id + " registers no variant");
  if (find(meta.id, meta.backend) != nullptr)
    throw std::logic_error("algorithm " + meta.id + "/" + meta.backend + " registered twice");
  algorithms_.push_back(std::move(algorithm));
}

const Algorithm* Registry::find(const std::string& id, const std::string& backend) const {
  for (const auto& a : algorithms_)
    if (a->info().id == id && a->info().backend == backend) return a.get();
  return nullptr;
}

}  // namespace shadowcts
