// Constexpr tables of named enum values (kShadowMethods, kRefractionMethods, kStepRules, ...): each entry an
// enum value, the name the CLI and reports spell, and a one-line summary for --help.
#pragma once

#include <string>
#include <string_view>

#include "util/error.h"

namespace voxr {

template <class Enum>
struct NamedValue {
  Enum value;
  const char* name;
  const char* summary;
};

// The entry of `table` for `value`. Throws InternalError when there is none.
template <class Table, class Enum>
const auto& named_entry(const Table& table, Enum value) {
  for (const auto& entry : table)
    if (entry.value == value) return entry;
  throw InternalError("a value missing from its name table");
}

// The value named `name`. Throws voxr::Error "unknown <what> '<name>' (known: a, b, c)".
template <class Table>
auto parse_named(const Table& table, std::string_view name, std::string_view what) {
  std::string known;
  for (const auto& entry : table) {
    if (name == entry.name) return entry.value;
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  }
  fail("unknown {} '{}' (known: {})", what, name, known);
}

}  // namespace voxr
