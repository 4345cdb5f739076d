#include "codec/scene_json.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <type_traits>

#include "codec/sample_table.h"
#include "engine/initial_rates.h"
#include "engine/number_text.h"
#include "engine/scene_fields.h"
#include "engine/simulation.h"
#include "engine/surface.h"

namespace spinfold {

using nlohmann::json;

namespace {

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
    if (!obj.contains(key)) return;
    double value = 0.0;
    const std::size_t before = count();
    number(obj, path, key, value);
    if (count() == before) out = value;
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

  // [x, y, z]: three numbers.
  void point(const json& j, const std::string& path, std::array<double, 3>& out) {
    if (j.is_array() && j.size() == 3 &&
        std::all_of(j.begin(), j.end(), [](const json& v) { return v.is_number(); })) {
      for (int k = 0; k < 3; ++k) out[k] = j[k].get<double>();
      return;
    }
    error(path, j, "must be a point [x, y, z] of three numbers");
  }

  // {"name": number, ...}: every value a number (the names' rules are the validator's).
  void named_numbers(const json& j, const std::string& path, SurfaceParameters& out) {
    if (!j.is_object()) {
      error(path, j, "must be a JSON object of named numbers, {\"a\": 2, \"b\": 1.3}");
      return;
    }
    SurfaceParameters read;
    const std::size_t before = count();
    for (const auto& [key, value] : j.items()) {
      if (value.is_number())
        read[key] = value.get<double>();
      else
        error(join(path, key), value, "must be a number");
    }
    if (count() == before) out = std::move(read);
  }

  // [[x₀, x₁], [y₀, y₁], [z₀, z₁]].
  void box(const json& j, const std::string& path, std::optional<SurfaceBounds>& out) {
    const auto pair = [](const json& r) {
      return r.is_array() && r.size() == 2 && r[0].is_number() && r[1].is_number();
    };
    if (j.is_array() && j.size() == 3 && std::all_of(j.begin(), j.end(), pair)) {
      SurfaceBounds b{};
      for (int k = 0; k < 3; ++k) b[k] = {j[k][0].get<double>(), j[k][1].get<double>()};
      out = b;
      return;
    }
    error(path, j, "must be a box [[x0, x1], [y0, y1], [z0, z1]] of numbers");
  }

  void error(const std::string& field, const json& value, const std::string& reason) {
    errors_.push_back({field, value.dump(), reason});
  }
  std::size_t count() const { return errors_.size(); }
  void add(FieldError e) { errors_.push_back(std::move(e)); }

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

// {"kind": name, fields of that kind...}: the alternative of a section chosen by kind (KindVariant:
// the deformation or height potential) that the kind names.
template <KindVariant V>
void read_kind_section(Reader& in, const json& j, const std::string& path, V& out) {
  if (!j.is_object()) {
    in.error(path, j, "must be a JSON object");
    return;
  }
  const auto kind = j.find("kind");
  const std::string name = kind != j.end() && kind->is_string() ? kind->get<std::string>() : "";
  bool known = false;
  std::string allowed;
  for_each_kind<V>([&](auto index, auto alternative) {
    using Alternative = typename decltype(alternative)::type;
    const std::string_view kind_name = kind_names(std::type_identity<V>{})[index];
    allowed += (allowed.empty() ? "" : ", ") + std::string(kind_name);
    if (known || name != kind_name) return;
    known = true;
    Alternative value;
    if (in.object(j, path, keys_of<Alternative>("kind"))) read_fields(in, j, path, value);
    out = value;
  });
  if (!known) in.error(path + ".kind", kind != j.end() ? *kind : json(nullptr), "must be one of: " + allowed);
}

// body.inertia as a matrix [[J11, J12], [J21, J22]] (engine/scene.h InertiaMatrix): read into
// inertia_matrix; true when `j` holds one (well-formed or not), so that the number reader skips it.
bool read_inertia_matrix(Reader& in, const json& j, const std::string& path, Body& out) {
  const auto it = j.find(kInertiaKey);
  if (it == j.end() || !it->is_array()) return false;
  const json& m = *it;
  const auto row = [](const json& r) {
    return r.is_array() && r.size() == 2 && r[0].is_number() && r[1].is_number();
  };
  if (m.size() != 2 || !row(m[0]) || !row(m[1])) {
    in.error(Reader::join(path, kInertiaKey), m,
             "must be a number (isotropic) or a 2x2 matrix [[J11, J12], [J21, J22]] of numbers");
    return true;
  }
  out.inertia_matrix = InertiaMatrix{m[0][0].get<double>(), m[0][1].get<double>(), m[1][0].get<double>(),
                                     m[1][1].get<double>()};
  return true;
}

// Reads every field of the table of S that `j` (an object) holds; absent ones keep their value.
template <typename S>
void read_table(Reader& in, const json& j, const std::string& path, S& out) {
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
      if constexpr (Point3<T>) {
        in.point(*it, sub, value);
      } else if constexpr (NamedNumbers<T>) {
        in.named_numbers(*it, sub, value);
      } else if constexpr (OptionalBox<T>) {
        in.box(*it, sub, value);
      } else if constexpr (HasFields<T>) {
        read_section(in, *it, sub, value);
      } else if constexpr (OptionalSection<T>) {
        value.emplace();
        read_section(in, *it, sub, *value);
      } else {
        static_assert(KindVariant<T>, "a field type the reader does not know");
        read_kind_section(in, *it, sub, value);
      }
    }
  });
  refuse_both_forms<S>(in, j, path);
}

// read_table, with body.inertia either a number or a matrix.
template <typename S>
void read_fields(Reader& in, const json& j, const std::string& path, S& out) {
  if constexpr (std::is_same_v<S, Body>) {
    const auto it = j.find(kInertiaKey);
    if (it != j.end() && it->is_number()) out.inertia_matrix.reset();  // a number: isotropic
    if (read_inertia_matrix(in, j, path, out)) {
      json rest = j;
      rest.erase(std::string(kInertiaKey));
      read_table(in, rest, path, out);
      return;
    }
  }
  read_table(in, j, path, out);
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

// The kinds a mask of surface_bit names, "sphere, pseudosphere or plane".
std::string surface_names(unsigned surfaces) {
  std::vector<std::string_view> names;
  for (const EnumName<SurfaceKind>& n : kSurfaceKindNames)
    if (surfaces & surface_bit(n.value)) names.push_back(n.name);
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i)
    text += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::string(names[i]);
  return text;
}

// A key of `j` (an object read as S, nested sections included) whose field does not belong to the
// surface `kind` (Field::surfaces): one error each, naming the kinds it belongs to.
template <typename S>
void refuse_other_surfaces(Reader& in, const json& j, const std::string& path, SurfaceKind kind) {
  if (!j.is_object()) return;
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const auto it = j.find(field.name);
    if (it == j.end()) return;
    const std::string sub = Reader::join(path, field.name);
    if (!belongs_to(field, kind)) {
      std::string reason = "is not defined on the " + std::string(enum_name(kind)) + ": only on the " +
                           surface_names(field.surfaces);
      if (std::is_same_v<S, InitialState>)
        reason += offers(kind, Offer::implicit_equation)
                      ? " (here the position is initial.u, its rate initial.u_dot)"
                      : " (here the position is initial.r, its rate initial.r_dot)";
      in.error(sub, *it, reason);
      return;
    }
    if constexpr (HasFields<T>)
      refuse_other_surfaces<T>(in, *it, sub, kind);
    else if constexpr (OptionalSection<T>)
      refuse_other_surfaces<typename T::value_type>(in, *it, sub, kind);
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
// Fields that do not belong to the surface `kind` (Field::surfaces) are left out.
template <typename S>
json write_fields(const S& in, SurfaceKind kind) {
  json j = json::object();
  const std::vector<std::string_view> replaced = replaced_fields(in);
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const T& value = in.*field.member;
    const std::string key(field.name);
    if (!belongs_to(field, kind)) return;
    if constexpr (std::is_same_v<T, double>) {
      if (std::find(replaced.begin(), replaced.end(), field.name) == replaced.end()) j[key] = value;
    } else if constexpr (OptionalNumber<T>) {
      if (value) j[key] = *value;
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (field.text_rule != TextRule::any || !value.empty()) j[key] = value;
    } else if constexpr (Enumerated<T>) {
      if (std::find(replaced.begin(), replaced.end(), field.name) == replaced.end())
        j[key] = enum_name(value);
    } else if constexpr (Point3<T>) {
      j[key] = json::array({value[0], value[1], value[2]});
    } else if constexpr (NamedNumbers<T>) {
      json named = json::object();
      for (const auto& [name, number] : value) named[name] = number;
      j[key] = named;
    } else if constexpr (OptionalBox<T>) {
      if (value)
        j[key] = json::array({json::array({(*value)[0][0], (*value)[0][1]}),
                              json::array({(*value)[1][0], (*value)[1][1]}),
                              json::array({(*value)[2][0], (*value)[2][1]})});
    } else if constexpr (HasFields<T>) {
      j[key] = write_fields(value, kind);
    } else if constexpr (OptionalSection<T>) {
      if (value) j[key] = write_fields(*value, kind);
    } else {
      static_assert(KindVariant<T>, "a field type the writer does not know");
      std::visit(
          [&](const auto& alternative) {
            using Alternative = std::remove_cvref_t<decltype(alternative)>;
            if constexpr (HasFields<Alternative>) {
              json d = write_fields(alternative, kind);
              d["kind"] = kind_names(std::type_identity<T>{})[value.index()];
              j[key] = d;
            }
          },
          value);
    }
  });
  if constexpr (std::is_same_v<S, Body>) {
    if (const auto& m = in.inertia_matrix)
      j[std::string(kInertiaKey)] =
          json::array({json::array({m->J11, m->J12}), json::array({m->J21, m->J22})});
  }
  return j;
}

// ---- Companions: merge patches over the main body's blocks, and fans (physics: test bodies do
// not interact, so each companion is a scene of its own on the same surface; engine/scene.h).

constexpr std::string_view kCompanionKeys[] = {"label",     "color",   "geodesic",  "body",
                                               "potential", "initial", "integrator"};

// The blocks a companion patches, as the main body's document gives them.
json companion_base(const json& document) {
  json base = json::object();
  for (const char* key : {"body", "initial", "integrator"})
    if (const auto it = document.find(key); it != document.end()) base[key] = *it;
  if (const auto p = document.find("potential"); p != document.end() && p->is_object())
    if (const auto d = p->find("deformation"); d != p->end()) base["potential"]["deformation"] = *d;
  return base;
}

// The point particle from the main body's start: same position and velocity, a rigid body of the
// same mass with zero spin (s = 2Jλ₀²(α̇ − β̇ + Cφ̇) = 0, physics.md §8.8; β̇ = 0) and no deformation
// force.
json geodesic_base(const Scene& main) {
  const InitialState& in = main.initial;
  const double scale = std::sqrt(in.lambda * in.mu);
  json initial = {{"alpha", in.alpha}, {"beta", in.beta}, {"lambda", scale}, {"mu", scale}, {"spin", 0.0}};
  if (offers(main.surface, Offer::formula)) {  // no chart: the start point, speed and heading
    initial["X"] = json::array({in.X[0], in.X[1], in.X[2]});
    if (in.speed && in.heading) {
      initial["speed"] = *in.speed;
      initial["heading"] = *in.heading;
    }
  } else {
    initial["phi"] = in.phi;
    initial["phi_dot"] = in.phi_dot;
    // The profile chart's u, else the polar chart's r.
    const bool profile = offers(main.surface, Offer::profile_chart);
    initial[profile ? "u" : "r"] = profile ? in.u : in.r;
    initial[profile ? "u_dot" : "r_dot"] = profile ? in.u_dot : in.r_dot;
  }
  return {{"body", {{"mass", main.body.mass}, {"inertia", main.body.inertia}, {"model", "rigid"}}},
          {"initial", initial}};
}

// The stand-in relation of the tables (Field::replaces), for a merge patch (RFC 7396): a patch of
// a block that sets an optional number drops the fields it stands in for from the base, and one
// that sets any of those drops it (spin ↔ alpha_dot; speed, heading ↔ r_dot, phi_dot; curvature ↔
// kind, radius), so that the patch's value wins instead of clashing. Nested sections likewise.
template <typename S>
void drop_replaced(json& base, const json& patch) {
  if (!base.is_object() || !patch.is_object()) return;
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const std::string name(field.name);
    if constexpr (OptionalNumber<T>) {
      const auto in_patch = [&](std::string_view r) { return !r.empty() && patch.contains(std::string(r)); };
      if (patch.contains(name)) {
        for (const std::string_view r : field.replaces)
          if (!r.empty()) base.erase(std::string(r));
      } else if (std::any_of(field.replaces.begin(), field.replaces.end(), in_patch)) {
        base.erase(name);
      }
    } else if constexpr (HasFields<T> || OptionalSection<T>) {
      const auto p = patch.find(name);
      const auto b = base.find(name);
      if (p == patch.end() || b == base.end()) return;
      if constexpr (HasFields<T>)
        drop_replaced<T>(*b, *p);
      else
        drop_replaced<typename T::value_type>(*b, *p);
    }
  });
}

// "#rrggbb" or [r, g, b] in [0, 1].
std::optional<std::array<double, 3>> read_color(Reader& in, const json& value, const std::string& path) {
  std::array<double, 3> rgb{};
  if (value.is_string()) {
    const std::string text = value.get<std::string>();
    if (text.size() == 7 && text[0] == '#' &&
        text.find_first_not_of("0123456789abcdefABCDEF", 1) == std::string::npos) {
      for (int k = 0; k < 3; ++k) rgb[k] = std::stoi(text.substr(1 + 2 * k, 2), nullptr, 16) / 255.0;
      return rgb;
    }
  } else if (value.is_array() && value.size() == 3 &&
             std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); })) {
    for (int k = 0; k < 3; ++k) rgb[k] = value[k].get<double>();
    return rgb;
  }
  in.error(path, value, "must be \"#rrggbb\" or [r, g, b] with components from 0 to 1");
  return std::nullopt;
}

// One companion entry over the main body: its blocks merged into the base and read as a scene.
std::optional<Companion> read_companion(Reader& in, const json& entry, const json& document,
                                        const Scene& main, const std::string& path) {
  const std::vector<std::string_view> keys(std::begin(kCompanionKeys), std::end(kCompanionKeys));
  if (!in.object(entry, path, keys)) return std::nullopt;
  Companion c;
  const std::size_t errors_before = in.count();
  in.text(entry, path, "label", c.label);
  if (const auto it = entry.find("color"); it != entry.end())
    c.color = read_color(in, *it, Reader::join(path, "color"));
  if (const auto it = entry.find("geodesic"); it != entry.end()) {
    if (it->is_boolean())
      c.geodesic = it->get<bool>();
    else
      in.error(Reader::join(path, "geodesic"), *it, "must be true or false");
  }
  if (const auto p = entry.find("potential"); p != entry.end())
    in.object(*p, Reader::join(path, "potential"), {"deformation"});
  json merged = companion_base(document);
  if (c.geodesic) {
    const json point = geodesic_base(main);
    merged["body"] = point["body"];
    merged["initial"] = point["initial"];
    merged.erase("potential");
  }
  for (const char* key : {"body", "integrator", "potential"})
    if (const auto it = entry.find(key); it != entry.end()) {
      if (!merged.contains(key)) merged[key] = json::object();
      merged[key].merge_patch(*it);
    }
  if (const auto it = entry.find("initial"); it != entry.end()) {
    refuse_other_surfaces<InitialState>(in, *it, Reader::join(path, "initial"), main.surface.kind);
    if (!merged.contains("initial")) merged["initial"] = json::object();
    drop_replaced<InitialState>(merged["initial"], *it);
    merged["initial"].merge_patch(*it);
  }
  Scene scene;
  if (const auto it = merged.find("body"); it != merged.end())
    read_section(in, *it, Reader::join(path, "body"), scene.body);
  if (const auto it = merged.find("initial"); it != merged.end())
    read_section(in, *it, Reader::join(path, "initial"), scene.initial);
  if (const auto it = merged.find("integrator"); it != merged.end())
    read_section(in, *it, Reader::join(path, "integrator"), scene.integrator);
  if (const auto p = merged.find("potential"); p != merged.end() && p->is_object())
    if (const auto d = p->find("deformation"); d != p->end() && !d->is_null())
      read_kind_section(in, *d, Reader::join(path, "potential.deformation"), scene.potential.deformation);
  if (in.count() != errors_before) return std::nullopt;
  // Its own spin, speed and heading on its own body and the shared surface.
  scene.surface = main.surface;
  for (FieldError& e : resolve_initial_rates(scene)) {
    e.field = path + "." + e.field;
    in.add(std::move(e));
  }
  if (in.count() != errors_before) return std::nullopt;
  c.body = scene.body;
  c.deformation = scene.potential.deformation;
  c.initial = scene.initial;
  c.integrator = scene.integrator;
  return c;
}

// A fan member's label: "spin = 0.25" (the field's last part and the value).
std::string fan_label(const std::string& last_part, double value) {
  return last_part + " = " + shortest(value);
}

// A dotted field path's parts: "initial.spin" → initial, spin.
std::vector<std::string> path_parts(const std::string& name) {
  std::vector<std::string> parts;
  for (std::size_t at = 0; at <= name.size();) {
    const std::size_t dot = std::min(name.find('.', at), name.size());
    parts.push_back(name.substr(at, dot - at));
    at = dot + 1;
  }
  return parts;
}

// {"field": "initial.spin", "values": [...]}: one companion entry per value, labelled by it.
std::vector<json> fan_entries(Reader& in, const json& vary) {
  std::vector<json> entries;
  if (!in.object(vary, "vary", {"field", "values"})) return entries;
  const auto field = vary.find("field");
  const auto values = vary.find("values");
  if (field == vary.end() || !field->is_string()) {
    in.error("vary.field", field == vary.end() ? json(nullptr) : *field,
             "must name a numeric field of body, initial or potential.deformation, e.g. \"initial.spin\"");
    return entries;
  }
  const std::vector<std::string> parts = path_parts(field->get<std::string>());
  const auto has = [](const std::vector<std::string_view>& keys, const std::string& key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  };
  std::vector<std::string_view> deformation_keys;
  for_each_kind<DeformationPotential>([&](auto, auto alternative) {
    for (std::string_view k : keys_of<typename decltype(alternative)::type>()) deformation_keys.push_back(k);
  });
  const bool numeric =
      (parts.size() == 2 && parts[0] == "body" && (parts[1] == "mass" || parts[1] == "inertia")) ||
      (parts.size() == 2 && parts[0] == "initial" && has(keys_of<InitialState>(), parts[1])) ||
      (parts.size() == 3 && parts[0] == "potential" && parts[1] == "deformation" && parts[2] != "kind" &&
       has(deformation_keys, parts[2]));
  if (!numeric) {
    in.error("vary.field", *field, "must name a numeric field of body, initial or potential.deformation");
    return entries;
  }
  if (values == vary.end() || !values->is_array() || values->empty() ||
      !std::all_of(values->begin(), values->end(), [](const json& v) { return v.is_number(); })) {
    in.error("vary.values", values == vary.end() ? json(nullptr) : *values,
             "must be a non-empty array of numbers");
    return entries;
  }
  for (const json& v : *values) {
    json patch = v;
    for (auto it = parts.rbegin(); it != parts.rend(); ++it) patch = json{{*it, patch}};
    patch["label"] = fan_label(parts.back(), v.get<double>());
    entries.push_back(patch);
  }
  return entries;
}

// The main body's label in a fan: its own value of the varied field, where the document gives it.
std::string fan_main_label(const json& document, const json& vary) {
  const auto field = vary.find("field");
  if (!vary.is_object() || field == vary.end() || !field->is_string()) return "";
  const json* at = &document;
  const std::vector<std::string> parts = path_parts(field->get<std::string>());
  for (const std::string& part : parts) {
    if (!at->is_object() || !at->contains(part)) return "";
    at = &(*at)[part];
  }
  return at->is_number() ? fan_label(parts.back(), at->get<double>()) : "";
}

// Expands "companions" and "vary" of the document into scene.companions (errors under
// companions[i], i counting the fan's entries after the listed ones).
void read_companions(Reader& in, const json& document, Scene& scene) {
  std::vector<json> entries;
  json source = json::object();
  if (const auto it = document.find("companions"); it != document.end()) {
    source["companions"] = *it;
    if (it->is_array())
      entries.assign(it->begin(), it->end());
    else
      in.error("companions", *it, "must be an array of companion objects");
  }
  if (const auto it = document.find("vary"); it != document.end()) {
    source["vary"] = *it;
    for (json& e : fan_entries(in, *it)) entries.push_back(std::move(e));
    scene.main_label = fan_main_label(document, *it);
  }
  if (source.empty()) return;
  scene.companions_source = source.dump();
  if (entries.size() > kMaxCompanions) {
    in.error("companions", json(entries.size()),
             "at most " + std::to_string(kMaxCompanions) + " companions (listed and from vary together)");
    return;
  }
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (auto c = read_companion(in, entries[i], document, scene, "companions[" + std::to_string(i) + "]"))
      scene.companions.push_back(std::move(*c));
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
  std::vector<std::string_view> keys = keys_of<Scene>();
  keys.insert(keys.end(), {"companions", "vary"});
  if (!in.object(document, "", keys)) return result;
  read_fields(in, document, "", scene);
  resolve_curvature(scene.surface);
  const std::size_t before_surfaces = result.errors.size();
  refuse_other_surfaces<Scene>(in, document, "", scene.surface.kind);
  // K with the fields of a surface whose curvature varies (a merge patch of surface.curvature on a
  // spheroid): the field at fault is curvature, which stands in for a kind of constant curvature;
  // the other kind's fields it then refuses (the surface's, initial.u, integrator.stepping) are one
  // error, named there.
  if (scene.surface.curvature_given && document.contains("surface")) {
    std::string others;
    for (std::size_t i = before_surfaces; i < result.errors.size(); ++i)
      if (result.errors[i].field.starts_with("surface."))
        others += (others.empty() ? "" : ", ") + result.errors[i].field.substr(8);
    if (!others.empty()) {
      result.errors.resize(before_surfaces);
      in.error(
          "surface.curvature", document["surface"]["curvature"],
          "stands in for the kind and radius of a surface of constant curvature (sphere, pseudosphere or "
          "plane), not with " +
              others + " of another kind: set surface.kind first, then K");
    }
  }

  // The rates from spin, speed and heading; then value errors too, except for fields already named
  // (whose structure was wrong, or which could not be converted).
  const auto add_new = [&](std::vector<FieldError> errors) {
    for (FieldError& e : errors) {
      const bool known = std::any_of(result.errors.begin(), result.errors.end(),
                                     [&](const FieldError& s) { return s.field == e.field; });
      if (!known) result.errors.push_back(std::move(e));
    }
  };
  // The rates are converted on the surface: one that is itself wrong (neck_radius 0) would make
  // them fail too and be named first, so a wrong surface is named alone.
  if (validate_surface(scene).empty()) add_new(resolve_initial_rates(scene));
  // Companions build on the main body: only once it reads and validates.
  if (result.errors.empty() && validate_scene(scene).empty()) read_companions(in, document, scene);
  std::vector<FieldError> invalid = validate_scene(scene);
  name_given_fields(invalid, "initial", scene.initial);
  for (std::size_t i = 0; i < scene.companions.size(); ++i)
    name_given_fields(invalid, "companions[" + std::to_string(i) + "].initial", scene.companions[i].initial);
  add_new(std::move(invalid));
  add_new(companion_label_errors(scene));
  if (result.errors.empty()) result.scene = scene;
  return result;
}

SceneParse parse_scene_text(std::string_view text) {
  SceneParse result;
  try {
    return parse_scene(parse_json_text(text));
  } catch (const JsonTextError& e) {
    result.errors.push_back({e.field, "", e.what()});
  }
  return result;
}

json scene_to_json(const Scene& scene) {
  const SurfaceKind kind = scene.surface.kind;
  json j = write_fields(scene, kind);
  if (!scene.companions_source.empty()) {
    const json source = json::parse(scene.companions_source);
    for (auto it = source.begin(); it != source.end(); ++it) j[it.key()] = it.value();
    return j;
  }
  // Companions made in code: each written whole (a merge patch that sets every field).
  for (const Companion& c : scene.companions) {
    json entry = {{"body", write_fields(c.body, kind)},
                  {"initial", write_fields(c.initial, kind)},
                  {"integrator", write_fields(c.integrator, kind)}};
    Scene holder;
    holder.potential.deformation = c.deformation;
    const json potential = write_fields(holder.potential, kind);
    entry["potential"] = {
        {"deformation", potential.contains("deformation") ? potential["deformation"] : json(nullptr)}};
    if (!c.label.empty()) entry["label"] = c.label;
    if (c.color) entry["color"] = *c.color;
    if (c.geodesic) entry["geodesic"] = true;
    j["companions"].push_back(entry);
  }
  return j;
}

void merge_scene_patch(json& document, const json& patch) {
  drop_replaced<Scene>(document, patch);
  document.merge_patch(patch);
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

std::string continued_reason(double t) {
  if (t == 0.0) return "new parameters from t = 0, continuing from the start";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", t);
  return std::string("new parameters from t = ") + text + " on, continuing from the current state";
}

std::string restart_reason(const json& patch, const Scene& before, const Scene& after) {
  if (patch.contains("initial")) return "the initial state changed: the run starts over at t = 0";
  if (patch.contains("companions") || patch.contains("vary") ||
      before.companions.size() != after.companions.size())
    return "the companions changed: the run starts over at t = 0";
  if (chart_free(before.surface) && before.surface.kind == after.surface.kind &&
      scene_to_json(before)["surface"] != scene_to_json(after)["surface"])
    return "the surface's shape changed: the run starts over at t = 0 on the new " +
           std::string(enum_name(after.surface.kind));
  if (before.surface.kind != after.surface.kind && !dialled(before.surface, after.surface))
    return "the surface changed kind: the run starts over at t = 0 on the new surface (give "
           "surface.curvature "
           "to dial through 0 without a restart)";
  // The incompressible body holds det L at the start's λμ: joining or leaving that constraint
  // mid-run would snap the shape to it (or leave its multiplier's momentum behind).
  if ((before.body.model == BodyModel::incompressible) != (after.body.model == BodyModel::incompressible))
    return "the body became or stopped being incompressible (its area is the start's): the run starts over "
           "at t = 0";
  return "";
}

}  // namespace spinfold
