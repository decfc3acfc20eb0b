#pragma once
// How the page shows JSON values it does not know in advance (error figures, counters, oracle
// figures of output kinds added later): flattened to dotted keys and formatted for reading, with
// the exact JSON text kept for data- attributes.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowcts {

// The leaves of an object as (dotted key, value) in document order. Nested objects are walked;
// arrays are leaves (the page plots or lists them rather than tabulating each element).
std::vector<std::pair<std::string, const nlohmann::ordered_json*>> flatten_fields(
    const nlohmann::ordered_json& object);

// A number for reading: integers in full with thin-space thousands separators, others with four
// significant digits. Plain text, not yet HTML-escaped.
std::string display_number(double value);

// Milliseconds for reading: two decimals from 1 ms up, three significant digits below.
std::string display_ms(double ms);

// Any JSON value for reading (plain text, not yet escaped): strings as they are, arrays of
// scalars joined with ", ", arrays of objects as their length, null as an em dash.
std::string display_value(const nlohmann::ordered_json& value);

// The value exactly as results.json spells it, for data-value attributes that tests compare.
std::string exact_text(const nlohmann::ordered_json& value);

}  // namespace shadowcts
