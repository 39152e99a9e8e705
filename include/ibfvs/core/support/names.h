#pragma once
// One name table per enum: parsing, printing, help texts, the docs and the
// viewer's lists all come from it, so a new value cannot be missing from one
// of them. An enum opts in by specialising EnumNames with a `table` of
// {value, name, description} entries (the first name of a value is its
// canonical one; later entries with the same value are accepted aliases).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

template <class E>
struct EnumName {
  E value;
  std::string_view name;         ///< what users type and what is printed
  std::string_view description;  ///< one phrase for help and docs; empty for an alias
};

/// Specialise with `static constexpr EnumName<E> table[] = {...};`.
template <class E>
struct EnumNames;

/// The canonical entries of E (aliases left out), in table order.
template <class E>
std::vector<EnumName<E>> enum_entries() {
  std::vector<EnumName<E>> out;
  for (const EnumName<E>& e : EnumNames<E>::table)
    if (!e.description.empty()) out.push_back(e);
  return out;
}

/// "a, b or c": the canonical names, for messages and help.
template <class E>
std::string enum_name_list(std::string_view last = " or ") {
  const std::vector<EnumName<E>> entries = enum_entries<E>();
  std::string out;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i > 0) out += i + 1 == entries.size() ? last : std::string_view(", ");
    out += entries[i].name;
  }
  return out;
}

/// The value named `text`; throws InputError "expected a, b or c, got 'x'".
template <class E>
E parse_enum(std::string_view text) {
  for (const EnumName<E>& e : EnumNames<E>::table)
    if (e.name == text) return e.value;
  throw InputError("expected " + enum_name_list<E>() + ", got '" + std::string(text) + "'");
}

/// The canonical name of `value`.
template <class E>
std::string_view enum_name(E value) {
  for (const EnumName<E>& e : EnumNames<E>::table)
    if (e.value == value) return e.name;
  return "?";
}

/// Position of `value` among enum_entries (for list widgets), -1 if absent.
template <class E>
int enum_index(E value) {
  const std::vector<EnumName<E>> entries = enum_entries<E>();
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (entries[i].value == value) return static_cast<int>(i);
  return -1;
}

}  // namespace ibfvs
