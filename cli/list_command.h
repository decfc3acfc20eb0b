#pragma once
#include <iosfwd>

namespace shadowcts {

class Registry;

// `shadowcts list [--json]`: fixtures, algorithms with variants and backends, capabilities.
void print_listing(const Registry& registry, bool json, std::ostream& out);

}  // namespace shadowcts
