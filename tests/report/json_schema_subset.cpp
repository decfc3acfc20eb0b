#include "json_schema_subset.h"

#include <cmath>
#include <set>
#include <stdexcept>

namespace shadowcts::test {
namespace {

using nlohmann::json;

const std::set<std::string> annotations = {"$schema",     "$id",      "title",
                                           "description", "$comment", "$defs"};
const std::set<std::string> assertions = {
    "type",      "properties",  "required", "additionalProperties",
    "items",     "prefixItems", "minItems", "maxItems",
    "enum",      "const",       "minimum",  "maximum",
    "minLength", "allOf",       "if",       "then",
    "else",      "$ref"};

bool has_type(const json& value, const std::string& type) {
  if (type == "object") return value.is_object();
  if (type == "array") return value.is_array();
  if (type == "string") return value.is_string();
  if (type == "boolean") return value.is_boolean();
  if (type == "null") return value.is_null();
  if (type == "number") return value.is_number();
  if (type == "integer")  // JSON Schema: a number with no fractional part, 1.0 included
    return value.is_number_integer() ||
           (value.is_number_float() && std::isfinite(value.get<double>()) &&
            value.get<double>() == std::floor(value.get<double>()));
  throw std::invalid_argument("schema: unknown type '" + type + "'");
}

std::size_t code_points(const std::string& utf8) {
  std::size_t n = 0;
  for (const char ch : utf8) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
  return n;
}

std::string pointer_token(const std::string& key) {
  std::string out;
  for (const char ch : key) out += ch == '~' ? "~0" : ch == '/' ? "~1" : std::string(1, ch);
  return out;
}

class Validator {
 public:
  explicit Validator(const json& root) : root_(root) {}

  void check(const json& schema, const json& value, const std::string& where,
             std::vector<std::string>& errors) const {
    if (schema.is_boolean()) {
      if (!schema.get<bool>()) errors.push_back(where + ": no value is allowed here");
      return;
    }
    if (!schema.is_object())
      throw std::invalid_argument("schema at " + where + " is not an object");
    for (const auto& [keyword, _] : schema.items())
      if (!annotations.count(keyword) && !assertions.count(keyword))
        throw std::invalid_argument("schema: unsupported keyword '" + keyword + "'");

    if (const auto ref = schema.find("$ref"); ref != schema.end())
      check_ref(*ref, value, where, errors);
    if (const auto type = schema.find("type"); type != schema.end()) {
      bool ok = false;
      if (type->is_array())
        for (const json& t : *type) ok |= has_type(value, t.get<std::string>());
      else
        ok = has_type(value, type->get<std::string>());
      if (!ok) errors.push_back(where + ": is " + value.type_name() + ", expected " + type->dump());
    }
    if (const auto c = schema.find("const"); c != schema.end() && value != *c)
      errors.push_back(where + ": is " + value.dump() + ", expected " + c->dump());
    if (const auto e = schema.find("enum"); e != schema.end()) {
      bool found = false;
      for (const json& option : *e) found |= value == option;
      if (!found) errors.push_back(where + ": " + value.dump() + " is not one of " + e->dump());
    }
    if (value.is_number()) {
      if (const auto m = schema.find("minimum");
          m != schema.end() && value.get<double>() < m->get<double>())
        errors.push_back(where + ": " + value.dump() + " is below the minimum " + m->dump());
      if (const auto m = schema.find("maximum");
          m != schema.end() && value.get<double>() > m->get<double>())
        errors.push_back(where + ": " + value.dump() + " is above the maximum " + m->dump());
    }
    if (value.is_string())
      if (const auto m = schema.find("minLength");
          m != schema.end() && code_points(value.get<std::string>()) < m->get<std::size_t>())
        errors.push_back(where + ": shorter than " + m->dump() + " characters");
    if (value.is_object()) check_object(schema, value, where, errors);
    if (value.is_array()) check_array(schema, value, where, errors);
    if (const auto all = schema.find("allOf"); all != schema.end())
      for (const json& sub : *all) check(sub, value, where, errors);
    if (const auto condition = schema.find("if"); condition != schema.end()) {
      std::vector<std::string> ignored;
      check(*condition, value, where, ignored);
      const auto branch = schema.find(ignored.empty() ? "then" : "else");
      if (branch != schema.end()) check(*branch, value, where, errors);
    }
  }

 private:
  void check_ref(const json& ref, const json& value, const std::string& where,
                 std::vector<std::string>& errors) const {
    const std::string target = ref.get<std::string>();
    const std::string prefix = "#/$defs/";
    if (target.rfind(prefix, 0) != 0)
      throw std::invalid_argument("schema: only #/$defs/NAME references are supported: " + target);
    const auto defs = root_.find("$defs");
    const std::string name = target.substr(prefix.size());
    if (defs == root_.end() || !defs->contains(name))
      throw std::invalid_argument("schema: dangling reference " + target);
    check(defs->at(name), value, where, errors);
  }

  void check_object(const json& schema, const json& value, const std::string& where,
                    std::vector<std::string>& errors) const {
    if (const auto required = schema.find("required"); required != schema.end())
      for (const json& key : *required)
        if (!value.contains(key.get<std::string>()))
          errors.push_back(where + ": required \"" + key.get<std::string>() + "\" is missing");
    const auto properties = schema.find("properties");
    const auto additional = schema.find("additionalProperties");
    for (const auto& [key, member] : value.items()) {
      const std::string at = where + "/" + pointer_token(key);
      if (properties != schema.end() && properties->contains(key))
        check(properties->at(key), member, at, errors);
      else if (additional != schema.end())
        check(*additional, member, at, errors);
    }
  }

  void check_array(const json& schema, const json& value, const std::string& where,
                   std::vector<std::string>& errors) const {
    if (const auto m = schema.find("minItems");
        m != schema.end() && value.size() < m->get<std::size_t>())
      errors.push_back(where + ": fewer than " + m->dump() + " items");
    if (const auto m = schema.find("maxItems");
        m != schema.end() && value.size() > m->get<std::size_t>())
      errors.push_back(where + ": more than " + m->dump() + " items");
    std::size_t first_item = 0;
    if (const auto prefix = schema.find("prefixItems"); prefix != schema.end()) {
      for (; first_item < prefix->size() && first_item < value.size(); ++first_item)
        check(prefix->at(first_item), value[first_item], where + "/" + std::to_string(first_item),
              errors);
      first_item = prefix->size();
    }
    if (const auto items = schema.find("items"); items != schema.end())
      for (std::size_t i = first_item; i < value.size(); ++i)
        check(*items, value[i], where + "/" + std::to_string(i), errors);
  }

  const json& root_;
};

}  // namespace

std::vector<std::string> schema_violations(const json& schema, const json& document) {
  std::vector<std::string> errors;
  Validator(schema).check(schema, document, "", errors);
  return errors;
}

}  // namespace shadowcts::test
