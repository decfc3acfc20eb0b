#pragma once
// The shell every algorithm backend is written in: a description (id, backend, summary,
// capabilities) and a declarative table of variants, each a name and what the name means (the
// backend's own configuration, the phases it times, the error it declares). The shell answers the
// Algorithm interface from them, looks variants up by name (the one "unknown variant" error),
// checks that the backend can run here at all (a device), and leaves the backend its run body and,
// where it has them, its own input checks.
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {

struct NoConfig {};

template <class Config = NoConfig>
struct AlgorithmVariant {
  std::string name{};
  Config config{};
  std::vector<std::string> phases = build_and_query_phases();  // Algorithm::timed_phases
  SoftErrorBudget soft_error_budget{};                         // soft_shadow outputs
  double robust_mismatch_ceiling = 0.0;                        // approximate hard shadows
};

// The rows `names`, in that order, each configured by config_of(name) and otherwise as `like`.
template <class ConfigOf>
auto variant_table(const std::vector<std::string>& names, ConfigOf config_of,
                   const AlgorithmVariant<>& like = {}) {
  using Config = std::decay_t<std::invoke_result_t<ConfigOf, const std::string&>>;
  std::vector<AlgorithmVariant<Config>> table;
  for (const std::string& name : names)
    table.push_back(
        {name, config_of(name), like.phases, like.soft_error_budget, like.robust_mismatch_ceiling});
  return table;
}

// The row named `name`; std::invalid_argument naming `who` for another name.
template <class Config>
const AlgorithmVariant<Config>& find_variant(const std::vector<AlgorithmVariant<Config>>& table,
                                             const std::string& name, const std::string& who) {
  for (const AlgorithmVariant<Config>& v : table)
    if (v.name == name) return v;
  throw std::invalid_argument(who + ": unknown variant '" + name + "'");
}

// The rows of `table` named `names`, in that order (a backend that ports some of another's).
template <class Config>
std::vector<AlgorithmVariant<Config>> select_variants(
    const std::vector<AlgorithmVariant<Config>>& table, const std::vector<std::string>& names) {
  std::vector<AlgorithmVariant<Config>> rows;
  for (const std::string& name : names) rows.push_back(find_variant(table, name, "select"));
  return rows;
}

// AlgorithmInfo less its variants, which the table gives.
struct AlgorithmDescription {
  std::string id;
  std::string backend;
  std::string summary;
  Capabilities capabilities{};
  // The registered variants (info().variants): every row of the table when empty, else these
  // (the table's other rows still run, for tests).
  std::vector<std::string> registered{};
  // Why the backend cannot run here at all (no device), or nullopt; nullptr: it always can.
  std::optional<std::string> (*unavailable_reason)() = nullptr;
  bool emulated = false;  // AlgorithmInfo::emulated
};

// What most hard-shadow algorithms declare.
inline constexpr Capabilities point_and_directional_hard_shadows{
    .output = OutputKind::hard_shadow, .point_light = true, .directional_light = true};

template <class Config = NoConfig>
class VariantTableAlgorithm : public Algorithm {
 public:
  using Variant = AlgorithmVariant<Config>;

  VariantTableAlgorithm(AlgorithmDescription description, std::vector<Variant> table)
      : table_(std::move(table)), unavailable_reason_(description.unavailable_reason) {
    info_.id = std::move(description.id);
    info_.backend = std::move(description.backend);
    info_.summary = std::move(description.summary);
    info_.capabilities = description.capabilities;
    info_.emulated = description.emulated;
    info_.variants = std::move(description.registered);
    if (info_.variants.empty())
      for (const Variant& v : table_) info_.variants.push_back(v.name);
    for (const std::string& name : info_.variants) variant(name);  // each one in the table
  }

  const AlgorithmInfo& info() const final { return info_; }

  std::vector<std::string> timed_phases(const std::string& name) const final {
    return variant(name).phases;
  }
  SoftErrorBudget soft_error_budget(const std::string& name) const final {
    return variant(name).soft_error_budget;
  }
  double robust_mismatch_ceiling(const std::string& name) const final {
    return variant(name).robust_mismatch_ceiling;
  }

  // Algorithm's checks (registered variant, capabilities), then the backend's input_problem,
  // then unavailable_reason.
  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& name) const override {
    if (auto why = Algorithm::unsupported_reason(c, samples, name)) return why;
    if (auto why = input_problem(c, samples, variant(name))) return why;
    return unavailable_reason();
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& name) const final {
    const Variant& v = variant(name);
    if (auto why = unavailable_reason()) throw std::runtime_error(*why);
    return run_variant(scene, v);
  }
  using Algorithm::run;

  const Variant& variant(const std::string& name) const {
    return find_variant(table_, name, info_.id + "/" + info_.backend);
  }

 protected:
  std::optional<std::string> unavailable_reason() const {
    return unavailable_reason_ ? unavailable_reason_() : std::nullopt;
  }

  // Why this backend cannot run the case's inputs (beyond its capabilities), or nullopt.
  virtual std::optional<std::string> input_problem(const Case&, const ViewSamples&,
                                                   const Variant&) const {
    return std::nullopt;
  }

  virtual AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const = 0;

 private:
  AlgorithmInfo info_;
  std::vector<Variant> table_;
  std::optional<std::string> (*unavailable_reason_)();
};

}  // namespace shadowcts
