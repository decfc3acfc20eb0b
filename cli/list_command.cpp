#include "list_command.h"

#include <iomanip>
#include <ostream>

#include <nlohmann/json.hpp>

#include "fixtures/fuzz/fuzz_fixtures.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/registry.h"

namespace shadowcts {
namespace {

std::string output_name(OutputKind kind) {
  switch (kind) {
    case OutputKind::hard_shadow:
      return "hard_shadow";
    case OutputKind::soft_shadow:
      return "soft_shadow";
    case OutputKind::light_lists:
      return "light_lists";
  }
  return "hard_shadow";
}

std::vector<std::string> light_kinds(const Capabilities& caps) {
  std::vector<std::string> kinds;
  if (caps.point_light) kinds.push_back("point");
  if (caps.directional_light) kinds.push_back("directional");
  if (caps.sun_disk) kinds.push_back("sun_disk");
  if (caps.ranged_lights) kinds.push_back("ranged");
  return kinds;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : separator) + item;
  return s;
}

}  // namespace

void print_listing(const Registry& registry, bool json, std::ostream& out) {
  if (json) {
    nlohmann::ordered_json root;
    root["fixtures"] = nlohmann::ordered_json::array();
    for (const FixtureGenerator& g : fixture_generators())
      root["fixtures"].push_back(
          {{"name", g.name}, {"summary", g.summary}, {"scalable", g.scalable}});
    root["default_fixtures"] = default_fixtures();
    root["stiff_fixtures"] = stiff_fixtures();
    root["fuzz_generators"] = fuzzing::fuzz_generator_names();
    root["algorithms"] = nlohmann::ordered_json::array();
    for (const auto& a : registry.algorithms()) {
      const AlgorithmInfo& m = a->info();
      root["algorithms"].push_back(
          {{"id", m.id},
           {"backend", m.backend},
           {"variants", m.variants},
           {"summary", m.summary},
           {"capabilities",
            {{"output", output_name(m.capabilities.output)},
             {"lights", light_kinds(m.capabilities)},
             {"needs_closed_meshes", m.capabilities.needs_closed_meshes},
             {"max_sample_triangle_pairs", m.capabilities.max_sample_triangle_pairs}}}});
    }
    out << root.dump(2) << "\n";
    return;
  }
  out << "fixtures (procedural ones take a size: <name>.<triangles>, e.g. gate_house.20k)\n";
  for (const FixtureGenerator& g : fixture_generators())
    out << "  " << std::left << std::setw(28) << g.name << g.summary << "\n";
  out << "\ndefault set: " << join(default_fixtures(), ", ") << "\n";
  out << "\nstiff suite (--suite stiff): " << join(stiff_fixtures(), ", ") << "\n";
  out << "\nfuzz cases: fuzz.<generator>.<seed>.<index>, generators "
      << join(fuzzing::fuzz_generator_names(), ", ")
      << " (e.g. fuzz.watertight.1.3; run, export and certify rebuild them from the name)\n";
  out << "\nalgorithms\n";
  for (const auto& a : registry.algorithms()) {
    const AlgorithmInfo& m = a->info();
    out << "  " << std::left << std::setw(14) << m.id << std::setw(11) << m.backend << "variants "
        << join(m.variants, ",") << "; " << output_name(m.capabilities.output) << "; lights "
        << join(light_kinds(m.capabilities), ",")
        << (m.capabilities.needs_closed_meshes ? "; needs closed meshes" : "") << "\n"
        << "  " << std::setw(25) << "" << m.summary << "\n";
  }
}

}  // namespace shadowcts
