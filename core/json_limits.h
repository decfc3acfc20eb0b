#pragma once
// Guards for JSON input (case manifests, glTF): bounded nesting before any parser sees the text,
// and bounded descriptions of values for error messages.
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace shadowcts {

// Deeper nesting than any manifest or glTF needs; tinygltf converts JSON recursively (100,000
// nested "extras" overflowed the stack), so the text is refused before it is parsed.
inline constexpr std::size_t max_json_depth = 512;

// Throws InputError(source, element, ...) when brackets outside strings nest deeper than
// max_depth, naming the depth and the line where it is exceeded. Linear, allocation-free: it
// does not check the syntax, the parser does that afterwards.
void check_json_nesting(std::string_view text, const std::string& source,
                        const std::string& element, std::size_t max_depth = max_json_depth);

// "<type> <first characters of the value>": at most about `limit` characters whatever the size
// or depth of the value, built without recursion (dump() recurses and copies everything).
std::string describe_json(const nlohmann::json& value, std::size_t limit = 40);

}  // namespace shadowcts
