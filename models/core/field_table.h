// Settings sections described once, by a table of fields (key, member, unit, range, one line of doc), which drives
// the scenario parser and its file:line errors, the validation of settings built in code, the `--set` key paths and
// the generated key tables of docs/SCENARIO_KEYS.md (in the spirit of MuJoCo's mjxmacro.h and Ceres'
// Solver::Options::IsValid). The default of a field is the initializer of its member: written once, in the struct.
//
// To add a field to a section: give the struct a member with its default, then one row in the section's table,
//   NumField<&SimulationSettings::voxel_mm>("voxel_mm", "mm", 0.1, 2.0, "voxel edge"),      // a number, int or size_t
//   NumField<&CellSettings::robot_base_mm>("base_mm", "mm", -2e4, 2e4, "arm base position"),  // std::array<double, N>
//   NanField<&ArcSettings::power_w>("power_w", "W", 1.0, 1e6, "arc power"),   // a double, NaN while absent
//   OptField<&SimulationSettings::blend>("blend", "corner blending of the executed path"),    // bool, enum, string
//   CustomField<CellSettings>("mjcf", FieldType::kFile, "MJCF model of the whole cell"),      // read by the section code
//   ListField<&SlicingSettings::sub_volumes, kSubVolumeFields, &FinishSubVolume>("sub_volumes", "..."),  // list of maps
//   NumberMapField<&ProgramFrames::uframe>("uframe", "frame", 1, 999, "mm, deg", -1e6, 1e6, "..."),  // {6: [...]}
//   EntryField<GeneratorParams>("size_mm", "mm", 0.1, 5000, 3, false, "..."),  // std::map<std::string, numbers>
// An enum member must have its EnumNames table (models/core/enum_names.h); its names are listed in the docs and in
// the parser's error. A list of maps has its element's own table (ListField: each element read, checked and named
// `key[i]`); a map keyed by numbers (NumberMapField: program.frames.uframe.6) holds numbers per key; an EntryField
// stores its value under its key in a std::map (tables built at run time, as the generators' parameters are, whose
// defaults come with the table: Describe(fields, defaults)). A Custom row reads nothing itself: the section's parser
// reads it (a path resolved against the scenario's folder, a value with two forms) and the row documents it and makes
// it a known key.
// Then run `waam scenario-keys > docs/SCENARIO_KEYS.md` (a test fails while the committed file differs).
// To add a section: a table `inline constexpr std::array kXFields = {...}` next to its struct, a parser that calls
// ReadFields (or ReadField per key where a key exists only for some types), a line in the section list of
// analysis/scenario_keys.cc (docs, --set key paths, validation), and a call in analysis::LoadScenario.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "models/core/enum_names.h"
#include "models/core/error.h"
#include "models/core/yaml_map.h"

namespace waam {

// What a key holds, as the docs name it.
enum class FieldType { kNumber, kInteger, kBool, kName, kString, kNumbers, kFile, kList, kMap };
constexpr std::array<EnumName<FieldType>, 9> EnumNames(FieldType) {
  return {{{FieldType::kNumber, "number"}, {FieldType::kInteger, "integer"}, {FieldType::kBool, "true/false"},
           {FieldType::kName, "name"}, {FieldType::kString, "string"}, {FieldType::kNumbers, "list of numbers"},
           {FieldType::kFile, "file"}, {FieldType::kList, "list"}, {FieldType::kMap, "mapping"}}};
}

// One key of a section of settings S.
template <typename S>
struct Field {
  std::string_view key;
  FieldType type = FieldType::kNumber;
  std::string_view unit;       // "mm", "deg", "mm/min", "" for a plain number
  double min = 0.0, max = 0.0;  // inclusive range of a number (of each number of a list)
  std::string_view doc;        // one line
  // Reads the key into `s` when present (keeps the member's value when absent); nullptr for a Custom row.
  void (*read)(YamlMap& map, const Field& field, S* s) = nullptr;
  // The member's value as the docs write it; nullptr for a Custom row.
  std::string (*show)(const Field& field, const S& s) = nullptr;
  // An enum's names ("none, fixed, speed"); nullptr unless type is kName.
  std::string (*names)() = nullptr;
  // The member's values as numbers, for the range check of settings built in code; nullptr if not numeric.
  std::vector<double> (*numbers)(const S& s) = nullptr;
  // The check of settings built in code for rows whose values are more than a list of numbers (a list of maps, a
  // number-keyed map, an entry of counted numbers): throws InputError naming "<section>.<key>..." and the rule.
  void (*check)(const Field& field, const S& s, std::string_view section) = nullptr;
  bool ranged = false;          // the docs show [min, max]
  int count = 1;                // EntryField: 1 one number (or a list of one), N a list of N, 0 a list of any length
  bool integer = false;         // EntryField: whole numbers
  // NumberMapField: what its keys number ("frame") and their range; the word that may stand for a value ("torch").
  std::string_view key_noun = {};
  int key_min = 0, key_max = 0;
  std::string_view word = {};
};

namespace field_internal {

template <typename M>
struct MemberOf;
template <typename C, typename V>
struct MemberOf<V C::*> {
  using Class = C;
  using Value = V;
};
template <typename V>
struct IsArray : std::false_type {};
template <std::size_t N>
struct IsArray<std::array<double, N>> : std::true_type {};
// std::vector<std::array<double, N>>: a flat list of groups of N numbers (half-spaces of 4, ...).
template <typename V>
struct IsGroups : std::false_type {};
template <std::size_t N>
struct IsGroups<std::vector<std::array<double, N>>> : std::true_type {
  static constexpr std::size_t kSize = N;
};
// The value an optional member holds when given (absent = std::nullopt); V itself otherwise.
template <typename V>
struct Given {
  using Type = V;
  static constexpr bool kOptional = false;
};
template <typename V>
struct Given<std::optional<V>> {
  using Type = V;
  static constexpr bool kOptional = true;
};

std::string ShowNumber(double value);

// Reads the number or the list of numbers `field` names (present) into `out`, each within the field's range.
template <typename T, typename F>
void ReadNumbers(YamlMap& map, const F& field, T* out) {
  const std::string key(field.key);
  if constexpr (IsArray<T>::value) {
    const std::vector<double> v = map.Numbers(key, static_cast<int>(T().size()), field.min, field.max);
    std::copy(v.begin(), v.end(), out->begin());
  } else if constexpr (IsGroups<T>::value) {
    constexpr std::size_t kN = IsGroups<T>::kSize;
    const std::vector<double> v = map.Numbers(key, -1, field.min, field.max);
    WAAM_THROW_UNLESS(v.size() % kN == 0, map.Where(key) << ": " << v.size() << " numbers: give " << kN
                                                         << " per entry (" << field.doc << ")");
    out->assign(v.size() / kN, {});
    for (std::size_t i = 0; i < v.size(); ++i) (*out)[i / kN][i % kN] = v[i];
  } else if constexpr (std::is_integral_v<T>) {
    *out = static_cast<T>(map.Integer(key, static_cast<int>(field.min), static_cast<int>(field.max)));
  } else {
    *out = static_cast<T>(map.Number(key, field.min, field.max));
  }
}

template <typename T>
std::vector<double> AsNumbers(const T& value) {
  if constexpr (IsArray<T>::value) {
    return std::vector<double>(value.begin(), value.end());
  } else if constexpr (IsGroups<T>::value) {
    std::vector<double> out;
    for (const auto& group : value) out.insert(out.end(), group.begin(), group.end());
    return out;
  } else {
    return {static_cast<double>(value)};
  }
}

template <typename T>
std::string ShowNumbers(const T& value) {
  if constexpr (IsArray<T>::value || IsGroups<T>::value) {
    std::string text = "[";
    for (double v : AsNumbers(value)) text += (text.size() > 1 ? ", " : "") + ShowNumber(v);
    return text + "]";
  } else {
    return ShowNumber(static_cast<double>(value));
  }
}

}  // namespace field_internal

// A numeric field: a double, an integer (a whole number; min and max within int), std::array<double, N> or
// std::vector<std::array<double, N>> (a flat list of groups of N, e.g. half-spaces), each number within [min, max]; or a std::optional of one of them, std::nullopt while the key is absent (the docs show
// no default: say in `doc` what absent means).
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> NumField(std::string_view key,
                                                                                 std::string_view unit, double min,
                                                                                 double max, std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using V = typename field_internal::MemberOf<decltype(kMember)>::Value;
  using T = typename field_internal::Given<V>::Type;
  constexpr bool kOptional = field_internal::Given<V>::kOptional;
  static_assert(field_internal::IsArray<T>::value || field_internal::IsGroups<T>::value ||
                    (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>),
                "NumField<> takes a number, std::array or a list of std::array, or a std::optional of one");
  Field<S> f{key, FieldType::kNumber, unit, min, max, doc};
  f.ranged = true;
  if constexpr (field_internal::IsArray<T>::value || field_internal::IsGroups<T>::value) {
    f.type = FieldType::kNumbers;
  } else if constexpr (std::is_integral_v<T>) {
    f.type = FieldType::kInteger;
  }
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    if (!map.Has(std::string(field.key))) return;
    T value{};
    if constexpr (!kOptional) value = s->*kMember;
    field_internal::ReadNumbers(map, field, &value);
    s->*kMember = value;
  };
  f.numbers = [](const S& s) {
    if constexpr (kOptional) {
      return s.*kMember ? field_internal::AsNumbers(*(s.*kMember)) : std::vector<double>{};
    } else {
      return field_internal::AsNumbers(s.*kMember);
    }
  };
  f.show = [](const Field<S>&, const S& s) {
    if constexpr (kOptional) {
      return s.*kMember ? field_internal::ShowNumbers(*(s.*kMember)) : std::string();
    } else {
      return field_internal::ShowNumbers(s.*kMember);
    }
  };
  return f;
}

// A double whose NaN means "not given" (the parser leaves it NaN while the key is absent; the docs show no default,
// and the range check skips it): for settings whose absence is a NaN member. Say in `doc` what absent means.
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> NanField(std::string_view key,
                                                                                 std::string_view unit, double min,
                                                                                 double max, std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  static_assert(std::is_same_v<typename field_internal::MemberOf<decltype(kMember)>::Value, double>,
                "NanField<> takes a double");
  Field<S> f = NumField<kMember>(key, unit, min, max, doc);
  f.numbers = [](const S& s) {
    const double v = s.*kMember;
    return std::isnan(v) ? std::vector<double>{} : std::vector<double>{v};
  };
  f.show = [](const Field<S>&, const S& s) {
    const double v = s.*kMember;
    return std::isnan(v) ? std::string() : field_internal::ShowNumber(v);
  };
  return f;
}

// A field without a range: bool, an enum with an EnumNames table, or std::string.
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> OptField(std::string_view key,
                                                                                 std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using V = typename field_internal::MemberOf<decltype(kMember)>::Value;
  Field<S> f{key, FieldType::kBool, "", 0.0, 0.0, doc};
  if constexpr (std::is_same_v<V, bool>) {
    f.read = [](YamlMap& map, const Field<S>& field, S* s) {
      s->*kMember = map.Bool(std::string(field.key), s->*kMember);
    };
    f.show = [](const Field<S>&, const S& s) { return std::string(s.*kMember ? "true" : "false"); };
  } else if constexpr (std::is_enum_v<V>) {
    f.type = FieldType::kName;
    f.read = [](YamlMap& map, const Field<S>& field, S* s) {
      s->*kMember = map.Enum(std::string(field.key), s->*kMember);
    };
    f.show = [](const Field<S>&, const S& s) { return std::string(NameOf(s.*kMember)); };
    f.names = [] { return EnumNameList<V>(); };
  } else {
    static_assert(std::is_same_v<V, std::string>, "OptField<> takes a bool, an enum or a std::string");
    f.type = FieldType::kString;
    f.read = [](YamlMap& map, const Field<S>& field, S* s) {
      s->*kMember = map.String(std::string(field.key), s->*kMember);
    };
    f.show = [](const Field<S>&, const S& s) { return s.*kMember; };
  }
  return f;
}

// A key the section's parser reads itself; the row documents it and makes it a known key.
template <typename S>
constexpr Field<S> CustomField(std::string_view key, FieldType type, std::string_view doc) {
  return Field<S>{key, type, "", 0.0, 0.0, doc};
}

// The row of `key` in `fields` (the code's mistake if there is none).
template <typename S>
const Field<S>& FieldOf(std::span<const Field<S>> fields, std::string_view key) {
  for (const Field<S>& f : fields) {
    if (f.key == key) return f;
  }
  internal::DemandFailed("the key has a row in its field table", __FILE__, __LINE__);
}

// Reads one key of `fields` into `s` when present; with `required`, a missing key is an InputError
// "file:line: section: missing required key 'key'".
template <typename S>
void ReadField(YamlMap& map, std::span<const Field<S>> fields, std::string_view key, S* s, bool required = false) {
  const Field<S>& f = FieldOf(fields, key);
  if (required) map.Require(std::string(key));
  f.read(map, f, s);
}

// Reads every key of `fields` that has a reader (Custom rows are the caller's) into `s`, in table order.
template <typename S>
void ReadFields(YamlMap& map, std::span<const Field<S>> fields, S* s) {
  for (const Field<S>& f : fields) {
    if (f.read) f.read(map, f, s);
  }
}

// Reads the nested mapping `key` of `map` when present (`parent.key: {...}`) with its own table `fields` into `s`, and
// refuses its unknown keys; returns whether the key was present. For a nested map with Custom rows, read it with
// map.Map(key), ReadFields and the section's own code, then CheckNoUnknownKeys.
template <typename S>
bool ReadFieldMap(YamlMap& map, std::string_view key, std::span<const Field<S>> fields, S* s) {
  if (!map.Has(std::string(key))) return false;
  YamlMap nested = map.Map(std::string(key));
  ReadFields(nested, fields, s);
  nested.CheckNoUnknownKeys();
  return true;
}

// Throws InputError "<section>.<key> = value: must be in [min, max]" for the first number of `s` outside its row's
// range: the check of settings built in code (a placement search, a sweep, an API) against the parser's limits.
template <typename S>
void CheckFields(std::span<const Field<S>> fields, const S& s, std::string_view section) {
  for (const Field<S>& f : fields) {
    if (f.check) f.check(f, s, section);
    if (!f.numbers) continue;
    for (double v : f.numbers(s)) {
      WAAM_THROW_UNLESS(std::isfinite(v) && v >= f.min && v <= f.max,
                        section << "." << f.key << " = " << v << ": must be in [" << f.min << ", " << f.max << "]");
    }
  }
}

// A list of maps (`key: [{...}, {...}]`), a std::vector<E> member whose element E has its own table kElementFields:
// each element read by ReadFields, then `kFinish(element_map, &e)` when given (required keys, rules across the
// element's keys), then its unknown keys refused; messages name `key[i]`. Absent: the member keeps its value.
template <auto kMember, const auto& kElementFields, auto kFinish = nullptr>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> ListField(std::string_view key,
                                                                                  std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using E = typename field_internal::MemberOf<decltype(kMember)>::Value::value_type;
  Field<S> f{key, FieldType::kList, "", 0.0, 0.0, doc};
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    if (!map.Has(std::string(field.key))) return;
    std::vector<E> list;
    for (YamlMap element : map.Maps(std::string(field.key))) {
      E e{};
      ReadFields<E>(element, kElementFields, &e);
      if constexpr (!std::is_null_pointer_v<decltype(kFinish)>) kFinish(element, &e);
      element.CheckNoUnknownKeys();
      list.push_back(std::move(e));
    }
    s->*kMember = std::move(list);
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    const std::vector<E>& list = s.*kMember;
    for (std::size_t i = 0; i < list.size(); ++i) {
      std::ostringstream path;
      path << section << "." << field.key << "[" << i << "]";
      CheckFields<E>(kElementFields, list[i], path.str());
    }
  };
  return f;
}

// A map from whole numbers to numbers (`key: {6: [x, y, z, w, p, r]}`): a std::map<int, V> member, V a
// std::array<double, N> each within [min, max], or a std::optional of one that `word` ("torch") leaves empty. Keys
// are `noun` numbers in [key_min, key_max]. Given, the map replaces the member's.
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> NumberMapField(
    std::string_view key, std::string_view noun, int key_min, int key_max, std::string_view unit, double min,
    double max, std::string_view doc, std::string_view word = {}) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using M = typename field_internal::MemberOf<decltype(kMember)>::Value;
  using V = typename M::mapped_type;
  using T = typename field_internal::Given<V>::Type;
  static_assert(std::is_same_v<typename M::key_type, int> && field_internal::IsArray<T>::value,
                "NumberMapField<> takes a std::map<int, std::array<double, N>> or of a std::optional of one");
  Field<S> f{key, FieldType::kMap, unit, min, max, doc};
  f.ranged = true;
  f.key_noun = noun;
  f.key_min = key_min;
  f.key_max = key_max;
  f.word = word;
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    if (!map.Has(std::string(field.key))) return;
    YamlMap table = map.Map(std::string(field.key));
    M out;
    for (const auto& [n, name] : table.NumberKeys(std::string(field.key_noun), field.key_min, field.key_max)) {
      if constexpr (field_internal::Given<V>::kOptional) {
        if (!field.word.empty() && !table.IsList(name) && table.String(name) == field.word) {
          out[n] = std::nullopt;
          continue;
        }
      }
      T value{};
      const std::vector<double> v = table.Numbers(name, static_cast<int>(value.size()), field.min, field.max);
      std::copy(v.begin(), v.end(), value.begin());
      out[n] = value;
    }
    table.CheckNoUnknownKeys();
    s->*kMember = std::move(out);
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    for (const auto& [n, value] : s.*kMember) {
      WAAM_THROW_UNLESS(n >= field.key_min && n <= field.key_max,
                        section << "." << field.key << "." << n << ": must be a " << field.key_noun
                                << " number in [" << field.key_min << ", " << field.key_max << "]");
      std::vector<double> numbers;
      if constexpr (field_internal::Given<V>::kOptional) {
        if (value) numbers = field_internal::AsNumbers(*value);
      } else {
        numbers = field_internal::AsNumbers(value);
      }
      for (double v : numbers) {
        WAAM_THROW_UNLESS(std::isfinite(v) && v >= field.min && v <= field.max,
                          section << "." << field.key << "." << n << " = " << v << ": must be in [" << field.min
                                  << ", " << field.max << "]");
      }
    }
  };
  f.show = [](const Field<S>&, const S&) { return std::string(); };
  return f;
}

// Numbers kept under their key in a std::map<std::string, std::vector<double>> (S): for tables built at run time
// whose keys depend on another key (part.generator's parameters by its type). `count`: 1 one number (or a list of
// one), N a list of N, 0 a list of any length; `integer`: whole numbers. The default is the defaults' entry
// (Describe(fields, defaults)). Messages of the check name "<section>.<key> = [values]".
template <typename S>
Field<S> EntryField(std::string_view key, std::string_view unit, double min, double max, int count, bool integer,
                    std::string_view doc) {
  Field<S> f{key, count == 1 ? (integer ? FieldType::kInteger : FieldType::kNumber) : FieldType::kNumbers,
             unit, min, max, doc};
  f.ranged = true;
  f.count = count;
  f.integer = integer;
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    std::vector<double> v = map.IsList(k) ? map.Numbers(k, field.count == 0 ? -1 : field.count, field.min, field.max)
                                          : std::vector<double>{map.Number(k, field.min, field.max)};
    WAAM_THROW_UNLESS(field.count <= 1 || static_cast<int>(v.size()) == field.count,
                      map.Where(k) << ": must be a list of " << field.count << " numbers (" << field.doc << ")");
    for (double x : v) {
      WAAM_THROW_UNLESS(!field.integer || x == std::round(x), map.Where(k) << " = " << x << ": must be a whole number");
    }
    (*s)[k] = std::move(v);
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    const auto it = s.find(std::string(field.key));
    if (it == s.end()) return;
    const std::vector<double>& v = it->second;
    std::string text = "[";
    for (double x : v) text += (text.size() > 1 ? ", " : "") + field_internal::ShowNumber(x);
    text += "]";
    const std::string where = std::string(section) + "." + std::string(field.key) + " = " + text;
    WAAM_THROW_UNLESS(field.count == 0 || static_cast<int>(v.size()) == field.count,
                      where << ": needs " << field.count << " value" << (field.count > 1 ? "s" : "") << " ("
                            << field.doc << ")");
    for (double x : v) {
      WAAM_THROW_UNLESS(std::isfinite(x) && x >= field.min && x <= field.max,
                        where << ": each value must be in [" << field.min << ", " << field.max << "] (" << field.doc
                              << ")");
      WAAM_THROW_UNLESS(!field.integer || x == std::round(x), where << ": must be whole numbers");
    }
  };
  f.show = [](const Field<S>& field, const S& s) {
    const auto it = s.find(std::string(field.key));
    if (it == s.end()) return std::string();
    std::string text = it->second.size() == 1 && field.count == 1 ? "" : "[";
    for (std::size_t i = 0; i < it->second.size(); ++i) {
      text += (i ? ", " : "") + field_internal::ShowNumber(it->second[i]);
    }
    return text + (text.empty() || text[0] != '[' ? "" : "]");
  };
  return f;
}

// A field as the docs show it: settings-type free, for the key tables and the `--set` key paths.
struct FieldInfo {
  std::string key;
  FieldType type = FieldType::kNumber;
  std::string unit;
  std::string default_text;  // the member's initial value; empty for a Custom row
  std::string range;         // "[min, max]" of a number, the names of an enum, or empty
  std::string doc;
};

// Every row of `fields` described, defaults from `defaults`.
template <typename S>
std::vector<FieldInfo> Describe(std::span<const Field<S>> fields, const S& defaults) {
  std::vector<FieldInfo> out;
  for (const Field<S>& f : fields) {
    FieldInfo info{std::string(f.key), f.type, std::string(f.unit), f.show ? f.show(f, defaults) : "", "",
                   std::string(f.doc)};
    if (f.names) info.range = f.names();
    if (f.ranged) {
      // Appended piece by piece: GCC 12's -Wrestrict misfires on `"[" + std::string&&` (its bug 105329).
      if (f.key_max > f.key_min) {
        info.range = std::string(f.key_noun);
        info.range += " ";
        info.range += std::to_string(f.key_min);
        info.range += "-";
        info.range += std::to_string(f.key_max);
        info.range += ": ";
      }
      info.range += "[";
      info.range += field_internal::ShowNumber(f.min);
      info.range += ", ";
      info.range += field_internal::ShowNumber(f.max);
      info.range += "]";
      if (!f.word.empty()) {
        info.range += " or ";
        info.range += f.word;
      }
    }
    out.push_back(std::move(info));
  }
  return out;
}

// Every row of `fields` described, defaults from a default-constructed S.
template <typename S>
std::vector<FieldInfo> Describe(std::span<const Field<S>> fields) {
  return Describe(fields, S{});
}

}  // namespace waam
