#pragma once
// A small enum's names as a table, for enums whose every value has one name: the name of a
// value and the value of a name. (Enums named by a switch keep the compiler's check that
// every value is named; this is for the two-valued ones a ternary named.)
#include <array>
#include <optional>
#include <string>
#include <utility>

namespace ldm {

template <typename E, size_t N>
using EnumNames = std::array<std::pair<E, const char*>, N>;

// `value`'s name ("?" for a value the table lacks).
template <typename E, size_t N>
const char* name_of(const EnumNames<E, N>& names, E value) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return "?";
}

// The value named `text`, or nothing for a name the table lacks.
template <typename E, size_t N>
std::optional<E> value_named(const EnumNames<E, N>& names, const std::string& text) {
  for (const auto& [v, name] : names)
    if (text == name) return v;
  return std::nullopt;
}

}  // namespace ldm
