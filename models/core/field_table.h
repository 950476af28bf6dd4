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
//   OptField<&ProgramSettings::format>("format", "...", "auto"),   // std::optional<enum>; "auto" stands for nullopt
//   WordsField<&CellSettings::robot_joints>("joints", "joint", 6, "..."),   // std::vector<std::string>, 6 words
//   FileField<&CellSettings::mjcf>("mjcf", "MJCF file", "..."),     // std::filesystem::path, relative to the scenario
//   FoldersField<&CellSettings::robot_package_paths>("package_paths", "..."),   // std::vector<std::filesystem::path>
//   RangeField<&PlaceSettings::part_x_mm>("part_x_mm", RowOf(kCellPartFields, "offset_mm"), "..."),  // [min, max, step]
//   NamesField<&ReplaySection::probes, kReplayProbeFields>("probes", "probe", "..."),   // {NAME: {...}}, std::vector<E>
//   TaggedField<&InterpassSettings::at, &InterpassSettings::probe, InterpassAt::kProbe>("at", "thermal.probes", "..."),
//                                                            // a name, or {probe: WORD} for the one value that takes one
//   MemberField<&ThermalSection::deposit, kThermalMaterialFields>("material"),  // a row of a member struct's table
// An enum member must have its EnumNames table (models/core/enum_names.h); its names are listed in the docs and in
// the parser's error. A list of maps has its element's own table (ListField: each element read, checked and named
// `key[i]`); a map keyed by numbers (NumberMapField: program.frames.uframe.6) holds numbers per key; an EntryField
// stores its value under its key in a std::map (tables built at run time, as the generators' parameters are, whose
// defaults come with the table: Describe(fields, defaults)). A file is taken relative to YamlMap::base_dir() (the
// scenario's folder) and checked where the document is loaded. A range's limits are another row's (RowOf), written
// once. A map keyed by the user's names (NamesField) holds a list of elements in file order, each a map with its own
// table or one row's value. A Custom row reads nothing itself: the section's parser reads it (a nested section with
// its own table) and the row documents it and makes it a known key. The kinds past OptField live in field_kinds.h.
// Then run `waam scenario-keys > docs/SCENARIO_KEYS.md` (a test fails while the committed file differs).
// To add a section: a table `inline constexpr std::array kXFields = {...}` next to its struct, a parser that calls
// ReadFields (or ReadField per key where a key exists only for some types), a line in the section list of
// analysis/scenario_keys.cc (docs, --set key paths, validation), and a call in analysis::LoadScenario.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

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
// A fixed-size Eigen column vector (a point in the part frame) reads and shows as a std::array does.
template <int N>
struct IsArray<Eigen::Matrix<double, N, 1>> : std::true_type {};
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
    const std::vector<double> v = map.Numbers(key, static_cast<int>(T{}.size()), field.min, field.max);
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

// A field without a range: bool, an enum with an EnumNames table, std::string, or a std::optional of an enum (absent:
// std::nullopt; with `word`, that word stands for std::nullopt too: program.format: auto; with `noun`, an unknown
// name is "<map>: unknown <noun> '<name>' (known: ...)", part.generator.type).
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> OptField(std::string_view key,
                                                                                 std::string_view doc,
                                                                                 std::string_view word = {},
                                                                                 std::string_view noun = {}) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using V = typename field_internal::MemberOf<decltype(kMember)>::Value;
  Field<S> f{key, FieldType::kBool, "", 0.0, 0.0, doc};
  f.word = word;
  f.key_noun = noun;
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
  } else if constexpr (field_internal::Given<V>::kOptional) {
    using E = typename field_internal::Given<V>::Type;
    static_assert(std::is_enum_v<E>, "OptField<> takes a std::optional of an enum");
    f.type = FieldType::kName;
    f.read = [](YamlMap& map, const Field<S>& field, S* s) {
      const std::string k(field.key);
      if (!map.Has(k)) return;
      if (field.word.empty() && field.key_noun.empty()) {
        s->*kMember = map.Enum<E>(k);
        return;
      }
      const std::string name = map.String(k);
      const std::optional<E> value = ParseEnum<E>(name);
      WAAM_THROW_UNLESS(value || field.key_noun.empty() || !field.word.empty(),
                        map.Where("") << ": unknown " << field.key_noun << " '" << name << "' (known: "
                                      << EnumNameList<E>() << ")");
      WAAM_THROW_UNLESS(value || name == field.word, map.Where(k) << " = '" << name << "': must be " << field.word
                                                                  << " or one of " << EnumNameList<E>());
      s->*kMember = value;
    };
    f.show = [](const Field<S>& field, const S& s) {
      return s.*kMember ? std::string(NameOf(*(s.*kMember))) : std::string(field.word);
    };
    f.names = [] { return EnumNameList<E>(); };
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

// The row of `key` in a table, in a constant expression (a table's limits taken by another's row: RangeField); a key
// without a row does not compile.
template <typename S, std::size_t N>
constexpr const Field<S>& RowOf(const std::array<Field<S>, N>& fields, std::string_view key) {
  for (const Field<S>& f : fields) {
    if (f.key == key) return f;
  }
  throw std::logic_error("RowOf: no row of this key");
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
    if (f.names) info.range = f.word.empty() ? f.names() : std::string(f.word) + ", " + f.names();
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

// The field kinds beyond numbers, names and words: lists, keyed maps, entries, files, folders and ranges.
#include "models/core/field_kinds.h"  // IWYU pragma: export
