#include "json_display.h"

#include <cmath>
#include <cstdio>

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

void flatten_into(const ordered_json& object, const std::string& prefix,
                  std::vector<std::pair<std::string, const ordered_json*>>& out) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object())
      flatten_into(*it, key, out);
    else
      out.emplace_back(key, &*it);
  }
}

std::string grouped_integer(long long value) {
  const std::string digits = std::to_string(value < 0 ? -value : value);
  std::string out = value < 0 ? "-" : "";
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += "\u2009";  // thin space
    out += digits[i];
  }
  return out;
}

}  // namespace

std::vector<std::pair<std::string, const ordered_json*>> flatten_fields(
    const ordered_json& object) {
  std::vector<std::pair<std::string, const ordered_json*>> out;
  if (object.is_object()) flatten_into(object, "", out);
  return out;
}

std::string display_number(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "NaN" : value > 0 ? "∞" : "-∞";
  if (value == std::floor(value) && std::fabs(value) < 1e15)
    return grouped_integer(static_cast<long long>(value));
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

std::string display_ms(double ms) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, ms >= 1 ? "%.2f" : "%.3g", ms);
  return buffer;
}

std::string display_value(const ordered_json& value) {
  if (value.is_null()) return "—";
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number()) return display_number(value.get<double>());
  if (value.is_array()) {
    bool scalars = true;
    for (const ordered_json& element : value) scalars &= !element.is_structured();
    if (!scalars) return std::to_string(value.size()) + " entries";
    std::string out;
    for (const ordered_json& element : value)
      out += (out.empty() ? "" : ", ") + display_value(element);
    return out;
  }
  return std::to_string(value.size()) + " fields";
}

std::string exact_text(const ordered_json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

}  // namespace shadowcts
