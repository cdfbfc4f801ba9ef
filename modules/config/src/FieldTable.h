#pragma once
// One table per config object: its keys, how each is read (type and range checks, messages
// naming the file and the key's full path), how it is written, and, through the object's own
// default member initialisers, its defaults. Unknown keys are rejected from the same table, so
// a key cannot be parsed without being written or written without being known. Each key
// carries its one-line description, and the tables describe themselves (describe(): key path,
// type, allowed values, default, description): docs/config-reference.md is made from them.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "mvw/config/ConfigReference.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

namespace mvw::config::detail {

using nlohmann::json;

// Where a value sits, for messages: the config file and the key's path ("render.views[0].zoom").
struct Where {
  const std::filesystem::path& file;
  std::string key;
  [[noreturn]] void bad(const std::string& problem) const {
    throw InputError(file, "'" + key + "' " + problem);
  }
};

// Never defined: a Doc that calls it cannot be made at compile time, which stops the build
// with this name in the message.
void a_config_field_needs_a_description();

// A key's one-line description, for the reference. A string literal that is not empty: every
// add/number/... takes one next to the key, so a key cannot be added without its description.
struct Doc {
  consteval Doc(const char* description) : text(description) {
    if (description == nullptr || description[0] == '\0') a_config_field_needs_a_description();
  }
  const char* text;
};

// How the reference shows a key that add() reads with its own code (the typed builders fill it
// in themselves).
struct Shape {
  std::string type;    // "object", "array of 2 numbers", ...
  std::string values;  // what it takes, in words ("" : any value of the type)
  // What an absent key means, in words ("required", "a still"); empty: the value the writer
  // writes for a default-constructed object (its default member initialisers), else "unset".
  std::string absent;
  // The keys of the object it holds, described below `path` (its own key path, with "[]" for an
  // array of objects); empty for a plain value.
  std::function<std::vector<ConfigKeyDoc>(const std::string& path)> below;
};

template <class E>
using EnumNames = std::vector<std::pair<E, const char*>>;

template <class E>
std::string namesOf(const EnumNames<E>& names) {
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i)
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::string(names[i].second);
  return list;
}

template <class E>
std::optional<E> parseName(const EnumNames<E>& names, const std::string& name) {
  for (const auto& [e, n] : names)
    if (name == n) return e;
  return std::nullopt;
}

template <class E>
std::string nameOf(const EnumNames<E>& names, E e) {
  for (const auto& [v, n] : names)
    if (v == e) return n;
  return "?";
}

// A number as a message shows it: 1e-300 and 1e+300, not 0.000000 and 300 digits, and enough
// digits that a value just beyond a limit does not print as the limit (4294967296, not 4.29e9).
inline std::string shortNumber(double x) { return mvw::shortNumber(x, 10); }

inline double readNumber(const json& v, const Where& w, double lo, double hi) {
  if (!v.is_number()) w.bad("must be a number");
  const double d = v.get<double>();
  if (!(d >= lo && d <= hi))
    w.bad("= " + shortNumber(d) + " is outside " + shortNumber(lo) + " .. " + shortNumber(hi));
  return d;
}

inline std::string readString(const json& v, const Where& w) {
  if (!v.is_string()) w.bad("must be a string");
  return v.get<std::string>();
}

template <class T>
class FieldTable {
 public:
  using Reader = std::function<void(const json& value, T& out, const Where& where)>;
  using Writer = std::function<void(const T& in, json& object, const char* key)>;

  FieldTable& add(const char* key, Doc doc, Shape shape, Reader read, Writer write) {
    fields_.push_back(
        {key, doc.text, std::move(read), std::move(write), std::nullopt, std::move(shape)});
    return *this;
  }

  // What the reference says an absent key means, for the key added last (where the writer's
  // value for a default object is not the whole story: a view's name is "view<N>").
  FieldTable& whenAbsent(std::string words) {
    fields_.back().shape.absent = std::move(words);
    return *this;
  }

  // The key added last is written only where `when` holds for the object (a value with an unset
  // form, written as absent: a window that is not set).
  FieldTable& writtenWhen(std::function<bool(const T&)> when) {
    fields_.back().write = [when, write = std::move(fields_.back().write)](const T& in, json& j,
                                                                           const char* k) {
      if (when(in)) write(in, j, k);
    };
    return *this;
  }

  template <class M>
  FieldTable& number(const char* key, Doc doc, M T::*member, double lo, double hi) {
    add(
        key, doc, {std::is_integral_v<M> ? "integer" : "number", rangeText(lo, hi), "", {}},
        [member, lo, hi](const json& v, T& out, const Where& w) {
          const double d = readNumber(v, w, lo, hi);
          // A count, a size or a seed: 48.5 is a mistake, not 48.
          if constexpr (std::is_integral_v<M>)
            if (d != std::floor(d)) w.bad("= " + shortNumber(d) + " must be a whole number");
          out.*member = static_cast<M>(d);
        },
        [member](const T& in, json& j, const char* k) { j[k] = in.*member; });
    fields_.back().range = std::pair{lo, hi};
    return *this;
  }

  FieldTable& optionalNumber(const char* key, Doc doc, std::optional<double> T::*member, double lo,
                             double hi) {
    add(
        key, doc, {"number", rangeText(lo, hi), "", {}},
        [member, lo, hi](const json& v, T& out, const Where& w) {
          out.*member = readNumber(v, w, lo, hi);
        },
        [member](const T& in, json& j, const char* k) {
          if (in.*member) j[k] = *(in.*member);
        });
    fields_.back().range = std::pair{lo, hi};
    return *this;
  }

  FieldTable& boolean(const char* key, Doc doc, bool T::*member) {
    return add(
        key, doc, {"boolean", "true or false", "", {}},
        [member](const json& v, T& out, const Where& w) {
          if (!v.is_boolean()) w.bad("must be true or false");
          out.*member = v.get<bool>();
        },
        [member](const T& in, json& j, const char* k) { j[k] = in.*member; });
  }

  FieldTable& string(const char* key, Doc doc, std::string T::*member) {
    return add(
        key, doc, {"string", "", "", {}},
        [member](const json& v, T& out, const Where& w) { out.*member = readString(v, w); },
        [member](const T& in, json& j, const char* k) { j[k] = in.*member; });
  }

  template <class E>
  FieldTable& enumeration(const char* key, Doc doc, E T::*member, EnumNames<E> names) {
    return add(
        key, doc, {"string", namesOf(names), "", {}},
        [member, names](const json& v, T& out, const Where& w) {
          const auto e = parseName(names, readString(v, w));
          if (!e) w.bad("must be " + namesOf(names));
          out.*member = *e;
        },
        [member, names](const T& in, json& j, const char* k) { j[k] = nameOf(names, in.*member); });
  }

  template <std::size_t N>
  FieldTable& numbers(const char* key, Doc doc, std::array<double, N> T::*member, double lo,
                      double hi) {
    return add(
        key, doc, numbersShape(N, lo, hi),
        [member, lo, hi](const json& v, T& out, const Where& w) {
          out.*member = readNumbers<N>(v, w, lo, hi);
        },
        [member](const T& in, json& j, const char* k) { j[k] = in.*member; });
  }

  // The same for a point or box corner (three numbers, written as an array).
  FieldTable& numbers(const char* key, Doc doc, glm::dvec3 T::*member, double lo, double hi) {
    return add(
        key, doc, numbersShape(3, lo, hi),
        [member, lo, hi](const json& v, T& out, const Where& w) {
          const std::array<double, 3> a = readNumbers<3>(v, w, lo, hi);
          out.*member = {a[0], a[1], a[2]};
        },
        [member](const T& in, json& j, const char* k) {
          const glm::dvec3& p = in.*member;
          j[k] = std::array<double, 3>{p.x, p.y, p.z};
        });
  }

  // A nested object whose presence switches on `enabled` of the member `value` ("glyphs":
  // {...} sets the glyph style's `on`), its keys read into this same struct by `table` (a value
  // type's keys, inlined there, beside keys of this struct's own); written only while it is on.
  template <class M>
  FieldTable& section(const char* key, Doc doc, M T::*value, bool M::*enabled,
                      const FieldTable<T>& table) {
    return add(
        key, doc,
        {"object", "", "off", [table](const std::string& path) { return table.describe(path); }},
        [value, enabled, table](const json& v, T& out, const Where& w) {
          (out.*value).*enabled = true;
          table.read(v, out, Where{w.file, w.key + "."});
        },
        [value, enabled, table](const T& in, json& j, const char* k) {
          if ((in.*value).*enabled) j[k] = table.write(in);
        });
  }

  // A value type's own table (one concept shared with the renderer, mvw/core: the crop, ...)
  // whose keys sit in this object beside its own: each is read into, and written from, the
  // member `value`, in the table's order, at this place in the reference.
  template <class M>
  FieldTable& inlined(M T::*value, const FieldTable<M>& table) {
    for (const auto& f : table.fields_)
      fields_.push_back({f.key, f.doc,
                         [value, read = f.read](const json& v, T& out, const Where& w) {
                           read(v, out.*value, w);
                         },
                         [value, write = f.write](const T& in, json& j, const char* k) {
                           write(in.*value, j, k);
                         },
                         f.range, f.shape});
    return *this;
  }

  // The keys named of a value type's own table, inlined here as above, in the order of `keys`
  // (so that a value's keys can keep their places among the object's own: the glyph style's
  // among the glyph map's). Every one must be in `table`; coveredKeys() checks the rest.
  template <class M>
  FieldTable& inlined(M T::*value, const FieldTable<M>& table,
                      std::initializer_list<const char*> keys) {
    for (const char* key : keys) {
      const typename FieldTable<M>::Field* f = table.find(key);
      if (f == nullptr) throw std::logic_error(std::string("no key '") + key + "' to inline");
      fields_.push_back({f->key, f->doc,
                         [value, read = f->read](const json& v, T& out, const Where& w) {
                           read(v, out.*value, w);
                         },
                         [value, write = f->write](const T& in, json& j, const char* k) {
                           write(in.*value, j, k);
                         },
                         f->range, f->shape});
    }
    return *this;
  }

  // Whether every key of `table` is a key of this one (each key of a value type's table
  // inlined in pieces, none left out).
  template <class M>
  bool coveredKeys(const FieldTable<M>& table) const {
    for (const auto& f : table.fields_)
      if (find(f.key) == nullptr) return false;
    return true;
  }

  // A value type's own table as a nested object whose presence switches it on ("depth_cue":
  // {...} sets `enabled` of the member `value`); written only while it is on.
  template <class M>
  FieldTable& section(const char* key, Doc doc, M T::*value, bool M::*enabled,
                      const FieldTable<M>& table) {
    return add(
        key, doc,
        {"object", "", "off", [table](const std::string& path) { return table.describe(path); }},
        [value, enabled, table](const json& v, T& out, const Where& w) {
          (out.*value).*enabled = true;
          table.read(v, out.*value, Where{w.file, w.key + "."});
        },
        [value, enabled, table](const T& in, json& j, const char* k) {
          if ((in.*value).*enabled) j[k] = table.write(in.*value);
        });
  }

  // `object`'s keys into `out` (keys not in the object keep out's values: the defaults).
  // where.key is the prefix of every key ("render.views[0]." or "" at the top).
  void read(const json& object, T& out, const Where& where) const {
    if (!object.is_object()) {
      std::string name = where.key;
      if (!name.empty() && name.back() == '.') name.pop_back();
      throw InputError(where.file, "'" + name + "' must be an object");
    }
    for (const auto& [key, value] : object.items()) {
      (void)value;
      if (find(key) == nullptr)
        throw InputError(where.file,
                         "unknown key '" + where.key + key + "' (known here: " + knownKeys() + ")");
    }
    for (const Field& f : fields_)
      if (object.contains(f.key)) f.read(object[f.key], out, Where{where.file, where.key + f.key});
  }

  json write(const T& in) const {
    json j = json::object();
    for (const Field& f : fields_) f.write(in, j, f.key);
    return j;
  }

  // The allowed range of a number field (number or optionalNumber); nullopt for another key.
  std::optional<std::pair<double, double>> range(const std::string& key) const {
    const Field* f = find(key);
    return f ? f->range : std::nullopt;
  }

  std::vector<std::string> keys() const {
    std::vector<std::string> keys;
    for (const Field& f : fields_) keys.push_back(f.key);
    return keys;
  }

  // Every key of the table, and of the objects its keys hold, as the reference shows them:
  // `object` is the key path of the table's object ("" at the top, "render.views[]").
  std::vector<ConfigKeyDoc> describe(const std::string& object) const {
    std::vector<ConfigKeyDoc> docs;
    const T defaults{};
    for (const Field& f : fields_) {
      ConfigKeyDoc d;
      d.object = object;
      d.key = object.empty() ? f.key : object + "." + f.key;
      d.type = f.shape.type;
      d.values = f.shape.values;
      d.description = f.doc;
      json written = json::object();
      if (f.shape.absent.empty()) f.write(defaults, written, f.key);
      if (written.contains(f.key)) {
        d.defaultValue = written[f.key].dump();
        d.defaultIsJson = true;
      } else {
        d.defaultValue = f.shape.absent.empty() ? "unset" : f.shape.absent;
      }
      docs.push_back(d);
      if (f.shape.below) {
        std::vector<ConfigKeyDoc> below = f.shape.below(d.key);
        docs.insert(docs.end(), below.begin(), below.end());
      }
    }
    return docs;
  }

  std::string knownKeys() const {
    std::vector<std::string> keys = this->keys();
    std::sort(keys.begin(), keys.end());
    std::string list;
    for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
    return list;
  }

 private:
  template <class>
  friend class FieldTable;
  struct Field {
    const char* key;
    const char* doc;
    Reader read;
    Writer write;
    std::optional<std::pair<double, double>> range;
    Shape shape;
  };
  static Shape numbersShape(std::size_t n, double lo, double hi) {
    return {"array of " + std::to_string(n) + " numbers", "each " + rangeText(lo, hi), "", {}};
  }
  template <std::size_t N>
  static std::array<double, N> readNumbers(const json& v, const Where& w, double lo, double hi) {
    const std::string what = "must be an array of " + std::to_string(N) + " numbers";
    if (!v.is_array() || v.size() != N) w.bad(what);
    std::array<double, N> a{};
    for (std::size_t i = 0; i < N; ++i) {
      if (!v[i].is_number()) w.bad(what);
      a[i] = v[i].get<double>();
      if (!(a[i] >= lo && a[i] <= hi))
        w.bad("values must lie in " + shortNumber(lo) + " .. " + shortNumber(hi));
    }
    return a;
  }
  static std::string rangeText(double lo, double hi) {
    return shortNumber(lo) + " .. " + shortNumber(hi);
  }
  const Field* find(const std::string& key) const {
    for (const Field& f : fields_)
      if (key == f.key) return &f;
    return nullptr;
  }
  std::vector<Field> fields_;
};

}  // namespace mvw::config::detail
