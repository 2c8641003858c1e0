// Lookups in a constexpr table of named enum values (kShadowMethods, kRefractionMethods, ...), each entry
// with a `name`; `key` picks the entry's enum member.
#pragma once

#include <string>
#include <string_view>

#include "core/error.h"

namespace voxr {

// The entry of `table` whose key(entry) == value. Throws InternalError when there is none.
template <class Table, class Key, class Value>
const auto& named_entry(const Table& table, Key key, Value value) {
  for (const auto& entry : table)
    if (key(entry) == value) return entry;
  throw InternalError("a value missing from its name table");
}

// The key of the entry named `name`. Throws voxr::Error "unknown <what> '<name>' (known: a, b, c)".
template <class Table, class Key>
auto parse_named(const Table& table, Key key, std::string_view name, std::string_view what) {
  std::string known;
  for (const auto& entry : table) {
    if (name == entry.name) return key(entry);
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  }
  fail("unknown {} '{}' (known: {})", what, name, known);
}

}  // namespace voxr
