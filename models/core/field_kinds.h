// The field kinds of models/core/field_table.h beyond numbers, names and words: a list of maps (ListField), a map keyed
// by numbers (NumberMapField), a map keyed by the user's names (NamesField), numbers kept under their key
// (EntryField), a list of words (WordsField), a file or a list of folders relative to the scenario (FileField,
// FoldersField), a searched [min, max, step] range (RangeField), a name or a tagged word (TaggedField), and a key whose
// value lives in a member struct (MemberField).
// Included by field_table.h; include that.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "models/core/field_table.h"

namespace waam {
namespace field_internal {

// Throws InputError "<where> = [min, max, step]: ..." for min > max, a negative step, or step 0 with min < max.
void CheckRange(double min, double max, double step, const std::string& where);

// Throws InputError naming `where` unless `words` has `field.count` words (count 0: at least one); then kEach on each.
template <auto kEach, typename F>
void CheckWords(const F& field, const std::vector<std::string>& words, const std::string& where) {
  if (field.count == 0) {
    WAAM_THROW_UNLESS(!words.empty(), where << ": must list at least one " << field.key_noun);
  } else {
    WAAM_THROW_UNLESS(static_cast<int>(words.size()) == field.count,
                      where << ": must list " << field.count << " " << field.key_noun << "s, got " << words.size());
  }
  if constexpr (!std::is_null_pointer_v<decltype(kEach)>) {
    for (const std::string& w : words) kEach(w, where);
  }
}

}  // namespace field_internal

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

// A list of words (`key: [a, b]`), a std::vector<std::string> member: `count` words exactly, or (count 0) at least one,
// each `noun`, each passed to kEach(word, where) when given (which throws InputError naming `where`). Absent: the
// member keeps its value; code-built settings are checked the same way when the list is not empty.
template <auto kMember, auto kEach = nullptr>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> WordsField(std::string_view key,
                                                                                   std::string_view noun, int count,
                                                                                   std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  static_assert(std::is_same_v<typename field_internal::MemberOf<decltype(kMember)>::Value, std::vector<std::string>>,
                "WordsField<> takes a std::vector<std::string>");
  Field<S> f{key, FieldType::kList, "", 0.0, 0.0, doc};
  f.key_noun = noun;
  f.count = count;
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    std::vector<std::string> words = map.Strings(k, {});
    field_internal::CheckWords<kEach>(field, words, map.Where(k));
    s->*kMember = std::move(words);
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    if ((s.*kMember).empty()) return;
    field_internal::CheckWords<kEach>(field, s.*kMember, std::string(section) + "." + std::string(field.key));
  };
  f.show = [](const Field<S>&, const S& s) {
    std::string text;
    for (const std::string& w : s.*kMember) text += (text.empty() ? "[" : ", ") + w;
    return text.empty() ? text : text + "]";
  };
  return f;
}

// A file named by a key (`key: path`), a std::filesystem::path member (empty: not given), resolved against the
// scenario's folder (YamlMap::base_dir) and recorded for CheckNamedFiles, which says "<noun> <path> not found" where
// the document is loaded. An empty name is refused.
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> FileField(std::string_view key,
                                                                                  std::string_view noun,
                                                                                  std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  static_assert(std::is_same_v<typename field_internal::MemberOf<decltype(kMember)>::Value, std::filesystem::path>,
                "FileField<> takes a std::filesystem::path");
  Field<S> f{key, FieldType::kFile, "", 0.0, 0.0, doc};
  f.key_noun = noun;
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    WAAM_THROW_UNLESS(!map.String(k).empty(), map.Where(k) << ": must name the " << field.key_noun);
    s->*kMember = map.File(k, map.base_dir(), std::string(field.key_noun));
  };
  f.show = [](const Field<S>&, const S& s) { return (s.*kMember).string(); };
  return f;
}

// A list of folders (`key: [dir, ...]`), a std::vector<std::filesystem::path> member, each relative to the scenario's
// folder (YamlMap::base_dir); not checked (a search path may name a folder that is absent).
template <auto kMember>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> FoldersField(std::string_view key,
                                                                                     std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  static_assert(std::is_same_v<typename field_internal::MemberOf<decltype(kMember)>::Value,
                               std::vector<std::filesystem::path>>,
                "FoldersField<> takes a std::vector<std::filesystem::path>");
  Field<S> f{key, FieldType::kList, "", 0.0, 0.0, doc};
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    std::vector<std::filesystem::path> out;
    for (const std::string& dir : map.Strings(k, {})) {
      std::filesystem::path d(dir);
      if (d.is_relative()) d = map.base_dir() / d;
      out.push_back(d.lexically_normal());
    }
    s->*kMember = std::move(out);
  };
  f.show = [](const Field<S>&, const S&) { return std::string(); };
  return f;
}

// A range searched over (`key: [min, max, step]`, or one number: that value only), a std::optional<R> member whose R
// has doubles min, max and step (absent: std::nullopt). The limits and unit are those of `limits`, the row of the key
// the range searches (RowOf(twin::kCellPartFields, "offset_mm")), so that they are written once. Refused: a value
// outside the limits, min > max, a negative step, step 0 with min < max (in the file and in code-built settings).
template <auto kMember, typename L>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> RangeField(std::string_view key,
                                                                                   const Field<L>& limits,
                                                                                   std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using V = typename field_internal::MemberOf<decltype(kMember)>::Value;
  static_assert(field_internal::Given<V>::kOptional, "RangeField<> takes a std::optional of {min, max, step}");
  using R = typename field_internal::Given<V>::Type;
  Field<S> f{key, FieldType::kNumbers, limits.unit, limits.min, limits.max, doc};
  f.ranged = true;
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    R r{};
    if (!map.IsList(k)) {
      r.min = r.max = map.Number(k, field.min, field.max);
    } else {
      const std::vector<double> v = map.Numbers(k, 3, field.min, field.max);
      r.min = v[0], r.max = v[1], r.step = v[2];
    }
    field_internal::CheckRange(r.min, r.max, r.step, map.Where(k));
    s->*kMember = r;
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    if (!(s.*kMember)) return;
    const R& r = *(s.*kMember);
    const std::string where = std::string(section) + "." + std::string(field.key);
    for (double v : {r.min, r.max}) {
      WAAM_THROW_UNLESS(std::isfinite(v) && v >= field.min && v <= field.max,
                        where << " = " << v << ": must be in [" << field.min << ", " << field.max << "]");
    }
    field_internal::CheckRange(r.min, r.max, r.step, where);
  };
  f.show = [](const Field<S>&, const S& s) {
    if (!(s.*kMember)) return std::string();
    const R& r = *(s.*kMember);
    if (r.step == 0.0 && r.min == r.max) return field_internal::ShowNumber(r.min);
    return "[" + field_internal::ShowNumber(r.min) + ", " + field_internal::ShowNumber(r.max) + ", " +
           field_internal::ShowNumber(r.step) + "]";
  };
  return f;
}

// A map keyed by the user's names (`key: {NAME: value, ...}`, YamlMap::Names(noun)), a std::vector<E> member in file
// order whose E has the members `name` (NAME) and `where` ("file:line: key.NAME"). kValueRow < 0: each value is a map
// read by the element's table kElementFields (replay.probes.NAME: {column, at_mm}), then `kFinish(element_map, &e)`
// when given (required keys, a `where` of its own), then its unknown keys refused. kValueRow = N: each value is row
// N's value itself (thermal.probes.NAME: [x, y, z]), and the docs give that row's unit and range. Given, the map
// replaces the member's; settings built in code are checked by the same rows, named `key.NAME`.
template <auto kMember, const auto& kElementFields, int kValueRow = -1, auto kFinish = nullptr>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> NamesField(std::string_view key,
                                                                                   std::string_view noun,
                                                                                   std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using E = typename field_internal::MemberOf<decltype(kMember)>::Value::value_type;
  Field<S> f{key, FieldType::kMap, "", 0.0, 0.0, doc};
  f.key_noun = noun;
  if constexpr (kValueRow >= 0) {
    const Field<E>& row = kElementFields[kValueRow];
    f.unit = row.unit, f.min = row.min, f.max = row.max, f.ranged = row.ranged;
  }
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    YamlMap names = map.Map(k);
    std::vector<E> list;
    for (const std::string& name : names.Names(std::string(field.key_noun))) {
      E e{};
      e.name = name;
      e.where = names.Where(name);
      if constexpr (kValueRow >= 0) {
        Field<E> row = kElementFields[kValueRow];
        row.key = name;  // the value under NAME read as the row's
        row.read(names, row, &e);
      } else {
        YamlMap element = names.Map(name);
        ReadFields<E>(element, kElementFields, &e);
        if constexpr (!std::is_null_pointer_v<decltype(kFinish)>) kFinish(element, &e);
        element.CheckNoUnknownKeys();
      }
      list.push_back(std::move(e));
    }
    names.CheckNoUnknownKeys();
    s->*kMember = std::move(list);
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    const std::string path = std::string(section) + "." + std::string(field.key);
    for (const E& e : s.*kMember) {
      if constexpr (kValueRow >= 0) {
        Field<E> row = kElementFields[kValueRow];
        row.key = e.name;
        CheckFields<E>(std::span<const Field<E>>(&row, 1), e, path);
      } else {
        CheckFields<E>(kElementFields, e, path + "." + e.name);
      }
    }
  };
  f.show = [](const Field<S>&, const S&) { return std::string(); };
  return f;
}

// A name of the enum member kMember, where the one value kTagged takes a word, written as a one-key map
// `{<kTagged's name>: WORD}` into the std::string member kWord (process.interpass.at: top_max, or {probe: NAME});
// `noun` says what the word names ("thermal.probes"). Refused: kTagged's name as a plain word ("<where> = probe: name
// the probe, as at: {probe: NAME}"), an empty word, and in settings built in code kTagged without a word.
template <auto kMember, auto kWord, auto kTagged>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> TaggedField(std::string_view key,
                                                                                    std::string_view noun,
                                                                                    std::string_view doc) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using E = typename field_internal::MemberOf<decltype(kMember)>::Value;
  static_assert(std::is_enum_v<E> && std::is_same_v<decltype(kTagged), E> &&
                    std::is_same_v<typename field_internal::MemberOf<decltype(kWord)>::Value, std::string>,
                "TaggedField<> takes an enum member, a std::string member and the enum's tagged value");
  Field<S> f{key, FieldType::kName, "", 0.0, 0.0, doc};
  f.key_noun = noun;
  f.names = [] { return EnumNameList<E>(); };
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const std::string k(field.key);
    if (!map.Has(k)) return;
    const std::string tag(NameOf(kTagged));
    if (map.IsMapping(k)) {
      YamlMap tagged = map.Map(k);
      s->*kMember = kTagged;
      s->*kWord = tagged.String(tag);
      WAAM_THROW_UNLESS(!(s->*kWord).empty(), tagged.Where(tag) << ": name one of " << field.key_noun);
      tagged.CheckNoUnknownKeys();
      return;
    }
    s->*kMember = map.Enum<E>(k);
    WAAM_THROW_UNLESS(s->*kMember != kTagged,
                      map.Where(k) << " = " << tag << ": name the " << tag << ", as " << field.key << ": {" << tag
                                   << ": NAME}");
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    const std::string tag(NameOf(kTagged));
    WAAM_THROW_UNLESS(s.*kMember != kTagged || !(s.*kWord).empty(),
                      section << "." << field.key << " = " << tag << ": name the " << tag << ", as " << field.key
                              << ": {" << tag << ": NAME}");
  };
  f.show = [](const Field<S>&, const S& s) { return std::string(NameOf(s.*kMember)); };
  return f;
}

// A key of S's section whose value lives in a member struct of S (replay.ambient_column in ReplayColumns,
// thermal.material in ThermalMaterialChoice): read, shown and checked as the row of the same key in kFields, the
// member struct's table, reads, shows and checks it on `s.*kMember`. `doc` replaces the row's when given (one row
// serving two sections: thermal.material, thermal.substrate.material).
template <auto kMember, const auto& kFields>
constexpr Field<typename field_internal::MemberOf<decltype(kMember)>::Class> MemberField(std::string_view key,
                                                                                    std::string_view doc = {}) {
  using S = typename field_internal::MemberOf<decltype(kMember)>::Class;
  using M = typename field_internal::MemberOf<decltype(kMember)>::Value;
  Field<S> f{};
  const Field<M>& row = RowOf(kFields, key);
  f.key = key, f.type = row.type, f.unit = row.unit, f.min = row.min, f.max = row.max;
  f.doc = doc.empty() ? row.doc : doc;
  f.names = row.names, f.ranged = row.ranged, f.count = row.count, f.integer = row.integer;
  f.key_noun = row.key_noun, f.key_min = row.key_min, f.key_max = row.key_max, f.word = row.word;
  f.read = [](YamlMap& map, const Field<S>& field, S* s) {
    const Field<M>& r = RowOf(kFields, field.key);
    if (r.read) r.read(map, r, &(s->*kMember));
  };
  f.show = [](const Field<S>& field, const S& s) {
    const Field<M>& r = RowOf(kFields, field.key);
    return r.show ? r.show(r, s.*kMember) : std::string();
  };
  f.check = [](const Field<S>& field, const S& s, std::string_view section) {
    const Field<M>& r = RowOf(kFields, field.key);
    CheckFields<M>(std::span<const Field<M>>(&r, 1), s.*kMember, section);
  };
  return f;
}

}  // namespace waam
