#pragma once
// A JSON Schema (draft 2020-12) validator for the keywords docs/results-schema.json uses. A schema
// with any other keyword is rejected rather than half-checked, so a test cannot pass by ignoring
// a constraint.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowcts::test {

// Supported: type, properties, required, additionalProperties, items, prefixItems, minItems,
// maxItems, enum, const, minimum, maximum, minLength, allOf, if/then/else, $ref to "#/$defs/NAME",
// $defs; annotations $schema, $id, title, description, $comment.
// Returns the violations as "<JSON pointer>: <problem>"; empty when the document is valid.
// Throws std::invalid_argument for a schema using anything else.
std::vector<std::string> schema_violations(const nlohmann::json& schema,
                                           const nlohmann::json& document);

}  // namespace shadowcts::test
