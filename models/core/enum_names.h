// Settings that take one of a closed set of names ("contour", "zigzag", ...) are enums parsed once at the boundary
// (scenario file, command line) from ONE table of names per enum, which the parser, its error message, --help and
// the name table of docs/SCENARIOS.md (checked by a test) all use. An enum E declares its table next to it, found by
// argument-dependent lookup:
//   enum class Blend { kNone, kFixed, kSpeed };
//   constexpr std::array<EnumName<Blend>, 3> EnumNames(Blend) {
//     return {{{Blend::kNone, "none"}, {Blend::kFixed, "fixed"}, {Blend::kSpeed, "speed"}}};
//   }
//   WAAM_ENUM_JSON(Blend)  // nlohmann::json writes the name, not the number
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace waam {

template <typename E>
struct EnumName {
  E value;
  std::string_view name;
};

// The name of `value` in its table ("?" for a value the table lacks, which a switch over the enum rules out).
template <typename E>
constexpr std::string_view NameOf(E value) {
  for (const EnumName<E>& entry : EnumNames(E{})) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}

// The value named `name`, or nothing.
template <typename E>
constexpr std::optional<E> ParseEnum(std::string_view name) {
  for (const EnumName<E>& entry : EnumNames(E{})) {
    if (entry.name == name) return entry.value;
  }
  return std::nullopt;
}

// Every name of E in table order, joined by `separator` ("contour, zigzag, hybrid").
template <typename E>
std::string EnumNameList(std::string_view separator = ", ") {
  std::string list;
  for (const EnumName<E>& entry : EnumNames(E{})) {
    if (!list.empty()) list += separator;
    list += entry.name;
  }
  return list;
}

}  // namespace waam

// Declares, in the namespace of enum E (where nlohmann::json looks for it), that a JSON value of E is its name:
// without it nlohmann::json would silently write the enum's number.
#define WAAM_ENUM_JSON(E)                                  \
  template <typename BasicJsonType>                        \
  void to_json(BasicJsonType& json, const E& value) {      \
    json = std::string(::waam::NameOf(value));             \
  }
