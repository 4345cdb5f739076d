#include "server/http/route_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>

#include "codec/scene_schema.h"
#include "engine/number_rule.h"
#include "engine/number_text.h"
#include "server/http/problem.h"  // (Eigen, through the engine: before httplib.h)
// clang-format off
#include "server/http/framing.h"  // (httplib.h)
// clang-format on

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// Session ids (server/sessions/session_id.h: 22 characters of base64url; a recording's is its session's and
// 22 more); any such text up to 44 characters routes, so that an unknown or malformed id gets the one
// 404 of an unknown session or recording.
constexpr const char* kIdPattern = "[A-Za-z0-9_-]{1,44}";

std::string joined(const std::vector<std::string>& items, const std::string& last) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  return text;
}

// A number parameter's rule (engine/number_rule.h).
NumberRule number_rule(const QueryParam& p) {
  Range range;
  if (p.minimum) range.min = *p.minimum;
  range.min_open = p.exclusive_minimum;
  if (p.maximum) range.max = *p.maximum;
  return {.whole = p.type == ParamType::integer, .range = range, .unit = p.unit};
}

// Why a value of this parameter is refused, e.g. "must be a whole number from 16 to 4096 [pixels]".
std::string expectation(const QueryParam& p) {
  switch (p.type) {
    case ParamType::integer:
    case ParamType::number: return must_be(number_rule(p));
    case ParamType::enumeration: return "must be " + joined(p.values, " or ");
    case ParamType::list: return "must be a comma-separated list of " + joined(p.values, ", ");
    case ParamType::string: break;
  }
  return "must be text";
}

// The value of one parameter, or the reason it is refused.
std::variant<QueryValue, std::string> parse_value(const QueryParam& p, const std::string& text) {
  switch (p.type) {
    case ParamType::integer: {  // the one reader and rule (engine/number_rule.h): 16.0 and 1e3 are whole
      const std::optional<double> x = number_from_text(text);
      if (!x || !allows(number_rule(p), *x)) return expectation(p);
      return QueryValue(static_cast<long long>(*x));
    }
    case ParamType::number: {
      const std::optional<double> x = number_from_text(text);
      if (!x || !allows(number_rule(p), *x)) return expectation(p);
      return QueryValue(*x);
    }
    case ParamType::enumeration:
      for (const std::string& v : p.values)
        if (v == text) return QueryValue(text);
      return expectation(p);
    case ParamType::list: {
      std::string_view rest = text;
      bool named = false;  // commas alone (`,`, `,,`) name nothing: refused, not read as absent
      while (true) {
        const std::size_t comma = rest.find(',');
        const std::string_view item = rest.substr(0, comma);
        bool known = item.empty();
        for (const std::string& v : p.values) known = known || v == item;
        if (!known) return "'" + std::string(item) + "' is not one of " + joined(p.values, ", ");
        named = named || !item.empty();
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
      if (!named && !text.empty()) return "names nothing: " + expectation(p);
      return QueryValue(text);
    }
    case ParamType::string: break;
  }
  return QueryValue(text);
}

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::integer: return "integer";
    case ParamType::number: return "number";
    case ParamType::enumeration:
    case ParamType::list:
    case ParamType::string: break;
  }
  return "string";
}

}  // namespace

std::vector<std::string> methods_of(const std::vector<Route>& routes, const std::string& path) {
  std::vector<std::string> methods;
  for (const Route& r : routes)
    if (r.path == path) methods.push_back(r.method);
  return methods;
}

ordered_json parameter_schema(const QueryParam& p) {
  ordered_json schema{{"type", type_name(p.type)}};
  if (p.type == ParamType::enumeration) schema["enum"] = p.values;
  if (p.type == ParamType::list)
    schema["pattern"] = "^(" + joined(p.values, "|") + "|)(,(" + joined(p.values, "|") + "|))*$";
  const auto bound = [&](double x) {
    return p.type == ParamType::integer ? ordered_json(static_cast<long long>(x)) : ordered_json(x);
  };
  // JSON Schema 2020-12 (OpenAPI 3.1): an exclusive bound is a number, not a flag on minimum.
  if (p.minimum) schema[p.exclusive_minimum ? "exclusiveMinimum" : "minimum"] = bound(*p.minimum);
  if (p.maximum) schema["maximum"] = bound(*p.maximum);
  if (p.default_value) std::visit([&](const auto& v) { schema["default"] = v; }, *p.default_value);
  if (!p.unit.empty()) schema["x-unit"] = p.unit;
  return schema;
}

// ---- Query values.

const QueryValue* Query::find(std::string_view name) const {
  bool known = false;
  if (declared_)
    for (const QueryParam& p : *declared_) known = known || p.name == name;
  if (!known) throw std::logic_error("query parameter not declared by the route: " + std::string(name));
  const auto it = values_.find(name);
  return it == values_.end() ? nullptr : &it->second;
}

std::optional<long long> Query::integer(std::string_view name) const {
  const QueryValue* v = find(name);
  if (!v) return std::nullopt;
  if (const auto* n = std::get_if<long long>(v)) return *n;
  throw std::logic_error("query parameter is not an integer: " + std::string(name));
}

std::optional<double> Query::number(std::string_view name) const {
  const QueryValue* v = find(name);
  if (!v) return std::nullopt;
  if (const auto* x = std::get_if<double>(v)) return *x;
  if (const auto* n = std::get_if<long long>(v)) return static_cast<double>(*n);
  throw std::logic_error("query parameter is not a number: " + std::string(name));
}

std::optional<std::string> Query::text(std::string_view name) const {
  const QueryValue* v = find(name);
  if (!v) return std::nullopt;
  if (const auto* s = std::get_if<std::string>(v)) return *s;
  throw std::logic_error("query parameter is not text: " + std::string(name));
}

Query parse_query(const Route& route, const httplib::Request& req) {
  // The query of the URL only (httplib's req.params also holds a form-encoded body's fields).
  httplib::Params given;
  if (const auto at = req.target.find('?'); at != std::string::npos)
    httplib::detail::parse_query_text(req.target.substr(at + 1), given);
  Query query(&route.query);
  std::vector<FieldError> errors;
  std::vector<std::string> names;
  for (const QueryParam& p : route.query) names.push_back(p.name);
  for (auto it = given.begin(); it != given.end(); it = given.upper_bound(it->first)) {
    const std::string& name = it->first;
    const QueryParam* param = nullptr;
    for (const QueryParam& p : route.query)
      if (p.name == name) param = &p;
    if (!param) {
      if (route.ignores_unknown_query) continue;
      errors.push_back({name, it->second,
                        "is not a query parameter of " + route.method + " " + route.path + " (" +
                            (names.empty() ? std::string("it takes none") : "known: " + joined(names, ", ")) +
                            ")"});
      continue;
    }
    if (given.count(name) > 1) {
      errors.push_back({name, it->second, "is given more than once"});
      continue;
    }
    auto value = parse_value(*param, it->second);
    if (auto* why = std::get_if<std::string>(&value))
      errors.push_back({name, it->second, *why});
    else
      query.set(name, std::get<QueryValue>(value));
  }
  if (!errors.empty()) throw ApiError{422, "Invalid query", errors, ""};
  for (const QueryParam& p : route.query)
    if (p.default_value && !given.count(p.name)) query.set(p.name, *p.default_value);
  return query;
}

// ---- The request body.

json Call::body() const {
  if (!route.body) throw std::logic_error(route.method + " " + route.path + " declares no body");
  return parse_body(http, body_text, route.body->content_types);
}

bool Call::has_body() const {
  return !body_text.empty();
}

// ---- Routing.

std::string path_regex(const std::string& path) {
  std::string regex;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path.compare(i, 4, "{id}") == 0) {
      regex += std::string("(") + kIdPattern + ")";
      i += 3;
    } else if (std::string_view(".^$|()[]{}*+?\\").find(path[i]) != std::string_view::npos) {
      regex += std::string("\\") + path[i];
    } else {
      regex += path[i];
    }
  }
  return regex;
}

// The body, read here rather than by httplib: Debian's cpp-httplib 0.11.4 holds a chunked body
// in memory whatever its size (its payload limit checks only Content-Length), so the reading stops
// at the limit and the request is refused (413). The answer says `Connection: close`, which clients
// heed; httplib itself keeps the connection and reads what follows as further (refused) requests,
// holding one line at a time: bounding those is the front's job (README, security model).
// httplib ends a chunked body early at a chunk not followed by CRLF, and says it was whole: the
// bytes as they arrived decide (server/http/framing.h), before the body is acted on, and before any
// other answer (a 405 too) is given to a request RFC 9112 says to refuse. ApiError 400 then.
void refuse_malformed_chunks(const httplib::Request& req, httplib::Response& res) {
  if (!req.has_header("Transfer-Encoding")) return;
  const std::string* bytes = current_request_bytes();
  if (!bytes) return;
  const Framing f = read_framing(*bytes);
  const ChunkedBody c = read_chunked(std::string_view(*bytes).substr(f.head_bytes));
  if (f.status == 0 && c.verdict == ChunkedBody::Verdict::complete && c.bytes == bytes->size() - f.head_bytes)
    return;
  if (req.get_header_value("Connection") != "close") res.set_header("Connection", "close");
  throw bad(400, "Malformed request", "Transfer-Encoding", "chunked",
            "malformed chunked body: " + (c.reason.empty() ? std::string("it ended early") : c.reason));
}

std::string bounded_body(const httplib::Request& req, const httplib::ContentReader& reader, std::size_t limit,
                         httplib::Response& res) {
  const auto close_connection = [&] {
    if (req.get_header_value("Connection") != "close") res.set_header("Connection", "close");
  };
  const std::string declared = req.get_header_value("Content-Length");
  if (declared.empty() && !req.has_header("Transfer-Encoding")) {
    if (req.method == "DELETE") return "";  // no body
    close_connection();                     // whatever follows cannot be told from a body
    throw bad(400, "Malformed request", "", "",
              "a " + req.method + " needs a Content-Length header (0 when there is no body)");
  }
  // Digits only (a sign or a space would still parse as a number): the front check of
  // server/http/framing.h says the same for a server that reads its own connections.
  if (!declared.empty() && declared.find_first_not_of("0123456789") != std::string::npos) {
    close_connection();
    throw bad(400, "Malformed request", "Content-Length", declared, "must be decimal digits only");
  }
  if (std::strtoull(declared.c_str(), nullptr, 10) > limit) {
    close_connection();
    throw bad(413, "Payload too large", "Content-Length", declared,
              "the request body exceeds the server's limit of " + std::to_string(limit) + " bytes");
  }
  std::string body;
  bool over = false;
  const bool whole = reader([&](const char* data, std::size_t length) {
    over = body.size() + length > limit;
    if (!over) body.append(data, length);
    return !over;
  });
  if (whole) {
    refuse_malformed_chunks(req, res);
    return body;
  }
  close_connection();
  if (over)
    throw bad(413, "Payload too large", "", "",
              "the request body exceeds the server's limit of " + std::to_string(limit) + " bytes");
  throw bad(400, "Malformed request", "", "", "the request body could not be read");
}

// ---- The OpenAPI document.

namespace {

// What the {id} of a path names.
std::string id_names(const std::string& path) {
  if (path.starts_with("/api/v1/recordings/")) return "recording";
  if (path.starts_with("/api/v1/work-precision/")) return "work-precision job";
  return "session";
}

}  // namespace

ordered_json openapi_document(const std::vector<Route>& routes) {
  const ordered_json problem_ref{{"$ref", "#/components/schemas/Problem"}};
  const ordered_json retry_after{{"description", "seconds to wait before trying again"},
                                 {"schema", {{"type", "integer"}, {"minimum", 0}}}};
  ordered_json paths = ordered_json::object();
  for (const Route& route : routes) {
    const bool has_id = route.path.find("{id}") != std::string::npos;
    std::vector<std::pair<int, std::string>> responses = route.responses;
    const auto add = [&](int status, const std::string& description) {
      for (const auto& r : responses)
        if (r.first == status) return;
      responses.emplace_back(status, description);
    };
    if (route.body) {
      add(400,
          "a body that is not exactly one JSON value (malformed, a NUL byte, trailing text), an empty body, "
          "or framing RFC 9112 refuses");
      add(413, "body over the size limit");
      add(415, "Content-Type not " + joined(route.body->content_types, " or "));
    }
    if (has_id) add(404, "unknown " + id_names(route.path) + ", or an encoded slash (%2F) in the path");
    // Every route: the framing check runs before routing (server/http/framing.h).
    add(400,
        "framing RFC 9112 refuses (two lengths, a signed length, Transfer-Encoding with Content-Length, "
        "obs-fold, a broken chunk)");
    add(501, "a Transfer-Encoding other than chunked");
    add(422, "an invalid value or an unknown query parameter (problem+json names them)");
    add(429, "over this client's request rate (limits.requests_per_second_per_client); Retry-After");
    std::sort(responses.begin(), responses.end());
    ordered_json answers = ordered_json::object();
    for (const auto& [status, description] : responses) {
      ordered_json answer{{"description", description}};
      // Every error is written by send_error (server/problem.cpp): RFC 9457 problem+json.
      if (status >= 400) answer["content"] = {{"application/problem+json", {{"schema", problem_ref}}}};
      if (status == 429 || status == 503) answer["headers"] = {{"Retry-After", retry_after}};
      answers[std::to_string(status)] = answer;
    }
    ordered_json operation{{"operationId", route.operation_id}, {"summary", route.summary}};
    ordered_json parameters = ordered_json::array();
    if (has_id)
      parameters.push_back(
          {{"name", "id"},
           {"in", "path"},
           {"required", true},
           {"description", "the " + id_names(route.path) + "'s id"},
           {"schema", {{"type", "string"}, {"pattern", std::string("^") + kIdPattern + "$"}}}});
    for (const QueryParam& p : route.query)
      parameters.push_back({{"name", p.name},
                            {"in", "query"},
                            {"required", false},
                            {"description", p.description},
                            {"schema", parameter_schema(p)}});
    if (!parameters.empty()) operation["parameters"] = parameters;
    if (route.body) {
      ordered_json content = ordered_json::object();
      for (const std::string& type : route.body->content_types)
        content[type] = {{"schema", route.body->schema}};
      operation["requestBody"] = {
          {"description", route.body->description}, {"required", route.body->required}, {"content", content}};
    }
    operation["responses"] = answers;
    std::string method = route.method;
    std::transform(method.begin(), method.end(), method.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    paths[route.path][method] = operation;
  }
  // What send_error writes (server/problem.cpp), every member always present.
  const ordered_json field_error{
      {"type", "object"},
      {"required", {"field", "value", "reason"}},
      {"properties",
       {{"field",
         {{"type", "string"},
          {"description", "the field, parameter or header refused (\"\" for the whole request)"}}},
        {"value", {{"type", "string"}, {"description", "the value given, as text (\"\" when none)"}}},
        {"reason", {{"type", "string"}, {"description", "why it is refused"}}}}}};
  const ordered_json problem{
      {"type", "object"},
      {"description", "An error (RFC 9457 problem details) naming each field, value and reason"},
      {"required", {"type", "title", "status", "detail", "errors"}},
      {"properties",
       {{"type", {{"type", "string"}, {"const", "about:blank"}}},
        {"title", {{"type", "string"}, {"description", "the kind of error, e.g. Invalid value"}}},
        {"status", {{"type", "integer"}, {"minimum", 400}, {"maximum", 599}}},
        {"detail",
         {{"type", "string"},
          {"description", "each error as \"field: reason (got value)\", joined by \"; \""}}},
        {"errors", {{"type", "array"}, {"items", field_error}}}}}};
  const ordered_json components{{"schemas", {{"Scene", scene_schema()}, {"Problem", problem}}}};
  return {{"openapi", "3.1.0"},
          {"jsonSchemaDialect", "https://json-schema.org/draft/2020-12/schema"},
          {"info",
           {{"title", "Spinfold API"},
            {"version", "1"},
            {"description",
             "Simulate an affinely-rigid body on a surface of constant curvature and draw it. There is "
             "no authentication: session and recording ids (22 characters of base64url, 128 random "
             "bits) are capabilities. They cannot be guessed, and whoever holds one can read, change "
             "and delete what it names, so share an id only with those who may. Errors are "
             "application/problem+json (RFC 9457)."}}},
          {"servers", {{{"url", "/"}}}},
          {"security", ordered_json::array()},
          {"paths", paths},
          {"components", components}};
}

}  // namespace spinfold::server
