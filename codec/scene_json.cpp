#include "codec/scene_json.h"

#include <algorithm>
#include <sstream>
#include <type_traits>

#include "engine/initial_rates.h"
#include "engine/number_text.h"
#include "engine/scene_fields.h"

namespace spinfold {

using nlohmann::json;

namespace {

struct TooDeep {};

// Reads one JSON object into plain fields, recording every problem with its dotted path.
class Reader {
 public:
  explicit Reader(std::vector<FieldError>& errors) : errors_(errors) {}

  // True if `j` is an object whose keys are all in `allowed`; unknown keys are errors.
  bool object(const json& j, const std::string& path, const std::vector<std::string_view>& allowed) {
    if (!j.is_object()) {
      error(path, j, "must be a JSON object");
      return false;
    }
    for (const auto& [key, value] : j.items())
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        error(join(path, key), value, "is not a known field here");
    return true;
  }

  void number(const json& obj, const std::string& path, std::string_view key, double& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_number())
      out = it->get<double>();
    else
      error(join(path, key), *it, "must be a number");
  }

  void optional_number(const json& obj, const std::string& path, std::string_view key,
                       std::optional<double>& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_number())
      out = it->get<double>();
    else
      error(join(path, key), *it, "must be a number");
  }

  void text(const json& obj, const std::string& path, std::string_view key, std::string& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_string())
      out = it->get<std::string>();
    else
      error(join(path, key), *it, "must be a string");
  }

  // A string that must be one of the enum's names (engine/scene_fields.h).
  template <Enumerated Enum>
  void choice(const json& obj, const std::string& path, std::string_view key, Enum& out) {
    const auto it = obj.find(key);
    if (it == obj.end()) return;
    if (it->is_string())
      if (const auto value = enum_value<Enum>(it->get<std::string>())) {
        out = *value;
        return;
      }
    std::string allowed;
    for (const EnumName<Enum>& n : enum_names(std::type_identity<Enum>{}))
      allowed += (allowed.empty() ? "" : ", ") + std::string(n.name);
    error(join(path, key), *it, "must be one of: " + allowed);
  }

  void error(const std::string& field, const json& value, const std::string& reason) {
    errors_.push_back({field, value.dump(), reason});
  }

  // Dotted path; a key that is empty or holds a dot is written quoted, so that the field named
  // is never "" (the whole document) nor ambiguous.
  static std::string join(const std::string& path, std::string_view key) {
    const std::string name = key.empty() || key.find('.') != std::string_view::npos
                                 ? json(std::string(key)).dump()
                                 : std::string(key);
    return path.empty() ? name : path + "." + name;
  }

 private:
  std::vector<FieldError>& errors_;
};

// The keys of a struct's table, after `first` (a deformation's "kind").
template <typename S>
std::vector<std::string_view> keys_of(std::optional<std::string_view> first = std::nullopt) {
  std::vector<std::string_view> keys;
  if (first) keys.push_back(*first);
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) { keys.push_back(field.name); });
  return keys;
}

template <typename S>
void read_fields(Reader& in, const json& j, const std::string& path, S& out);
template <typename S>
void refuse_both_forms(Reader& in, const json& j, const std::string& path);

// A section: reads `j` into `out` when it is an object of known keys.
template <typename S>
void read_section(Reader& in, const json& j, const std::string& path, S& out) {
  if (in.object(j, path, keys_of<S>())) read_fields(in, j, path, out);
}

// {"kind": name, fields of that kind...}: the alternative of DeformationPotential named by kind.
void read_deformation(Reader& in, const json& j, const std::string& path, DeformationPotential& out) {
  if (!j.is_object()) {
    in.error(path, j, "must be a JSON object");
    return;
  }
  const auto kind = j.find("kind");
  const std::string name = kind != j.end() && kind->is_string() ? kind->get<std::string>() : "";
  bool known = false;
  std::string allowed;
  for_each_deformation_kind([&](auto index, auto alternative) {
    using Alternative = typename decltype(alternative)::type;
    const std::string_view kind_name = kDeformationKindNames[index];
    allowed += (allowed.empty() ? "" : ", ") + std::string(kind_name);
    if (known || name != kind_name) return;
    known = true;
    Alternative value;
    if (in.object(j, path, keys_of<Alternative>("kind"))) read_fields(in, j, path, value);
    out = value;
  });
  if (!known) in.error(path + ".kind", kind != j.end() ? *kind : json(nullptr), "must be one of: " + allowed);
}

// Reads every field of the table of S that `j` (an object) holds; absent ones keep their value.
template <typename S>
void read_fields(Reader& in, const json& j, const std::string& path, S& out) {
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    T& value = out.*field.member;
    if constexpr (std::is_same_v<T, double>) {
      in.number(j, path, field.name, value);
    } else if constexpr (OptionalNumber<T>) {
      in.optional_number(j, path, field.name, value);
    } else if constexpr (std::is_same_v<T, std::string>) {
      in.text(j, path, field.name, value);
    } else if constexpr (Enumerated<T>) {
      in.choice(j, path, field.name, value);
    } else {
      const auto it = j.find(field.name);
      if (it == j.end()) return;
      const std::string sub = Reader::join(path, field.name);
      if constexpr (HasFields<T>) {
        read_section(in, *it, sub, value);
      } else if constexpr (OptionalSection<T>) {
        value.emplace();
        read_section(in, *it, sub, *value);
      } else {
        static_assert(std::is_same_v<T, DeformationPotential>, "a field type the reader does not know");
        read_deformation(in, *it, sub, value);
      }
    }
  });
  refuse_both_forms<S>(in, j, path);
}

// An optional number given in the same block as a field it stands in for (spin with alpha_dot):
// one error per such pair, naming both.
template <typename S>
void refuse_both_forms(Reader& in, const json& j, const std::string& path) {
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (OptionalNumber<T>) {
      const auto it = j.find(field.name);
      if (it == j.end()) return;
      for (const std::string_view replaced : field.replaces)
        if (!replaced.empty() && j.contains(replaced))
          in.error(Reader::join(path, field.name), *it,
                   "give either " + std::string(field.name) + " or " + std::string(replaced) + ", not both");
    }
  });
}

// The fields of S that a set optional number stands in for (alpha_dot when spin is set).
template <typename S>
std::vector<std::string_view> replaced_fields(const S& in) {
  std::vector<std::string_view> replaced;
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (OptionalNumber<T>)
      if (in.*field.member)
        for (const std::string_view name : field.replaces)
          if (!name.empty()) replaced.push_back(name);
  });
  return replaced;
}

// The JSON of every field of the table of S (informational text only when not empty, absent
// optional numbers, optional sections and deformations omitted, and a number omitted when a set
// optional number stands in for it: the scene is written as it was given).
template <typename S>
json write_fields(const S& in) {
  json j = json::object();
  const std::vector<std::string_view> replaced = replaced_fields(in);
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const T& value = in.*field.member;
    const std::string key(field.name);
    if constexpr (std::is_same_v<T, double>) {
      if (std::find(replaced.begin(), replaced.end(), field.name) == replaced.end()) j[key] = value;
    } else if constexpr (OptionalNumber<T>) {
      if (value) j[key] = *value;
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (field.text_rule != TextRule::any || !value.empty()) j[key] = value;
    } else if constexpr (Enumerated<T>) {
      j[key] = enum_name(value);
    } else if constexpr (HasFields<T>) {
      j[key] = write_fields(value);
    } else if constexpr (OptionalSection<T>) {
      if (value) j[key] = write_fields(*value);
    } else {
      static_assert(std::is_same_v<T, DeformationPotential>, "a field type the writer does not know");
      std::visit(
          [&](const auto& alternative) {
            using Alternative = std::remove_cvref_t<decltype(alternative)>;
            if constexpr (HasFields<Alternative>) {
              json d = write_fields(alternative);
              d["kind"] = kDeformationKindNames[value.index()];
              j[key] = d;
            }
          },
          value);
    }
  });
  return j;
}

// Errors about a rate that a given optional number filled name that number instead: the scene
// said spin, not alpha_dot.
template <typename S>
void name_given_fields(std::vector<FieldError>& errors, const std::string& path, const S& in) {
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (OptionalNumber<T>) {
      const T& value = in.*field.member;
      if (!value) return;
      for (const std::string_view replaced : field.replaces)
        for (FieldError& e : errors)
          if (!replaced.empty() && e.field == Reader::join(path, replaced)) {
            e.field = Reader::join(path, field.name);
            e.value = shortest(*value);
          }
    }
  });
}

}  // namespace

SceneParse parse_scene(const json& document) {
  SceneParse result;
  Reader in(result.errors);
  Scene scene;
  if (!in.object(document, "", keys_of<Scene>())) return result;
  read_fields(in, document, "", scene);

  // The rates from spin, speed and heading; then value errors too, except for fields already named
  // (whose structure was wrong, or which could not be converted).
  const auto add_new = [&](std::vector<FieldError> errors) {
    for (FieldError& e : errors) {
      const bool known = std::any_of(result.errors.begin(), result.errors.end(),
                                     [&](const FieldError& s) { return s.field == e.field; });
      if (!known) result.errors.push_back(std::move(e));
    }
  };
  add_new(resolve_initial_rates(scene));
  std::vector<FieldError> invalid = validate_scene(scene);
  name_given_fields(invalid, "initial", scene.initial);
  add_new(std::move(invalid));
  if (result.errors.empty()) result.scene = scene;
  return result;
}

SceneParse parse_scene_text(std::string_view text) {
  SceneParse result;
  try {
    const json::parser_callback_t depth_guard = [](int depth, json::parse_event_t, json&) {
      if (depth > kMaxJsonDepth) throw TooDeep{};
      return true;
    };
    return parse_scene(json::parse(text, depth_guard));
  } catch (const TooDeep&) {
    result.errors.push_back({"", "", "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"});
  } catch (const json::exception& e) {
    result.errors.push_back({"", "", std::string("malformed JSON: ") + e.what()});
  }
  return result;
}

json scene_to_json(const Scene& scene) {
  return write_fields(scene);
}

std::string describe_errors(const std::vector<FieldError>& errors) {
  std::ostringstream out;
  for (const FieldError& e : errors) {
    out << (e.field.empty() ? "scene" : e.field) << ": " << e.reason;
    if (!e.value.empty()) out << " (got " << e.value << ")";
    out << "\n";
  }
  return out.str();
}

}  // namespace spinfold
