// The HTTP API as one table: each route is one row of data (method, path, handler, summary, typed
// query parameters, request body, responses). From the table come the router's registrations, the
// 405 answers with `Allow`, the parsing and checking of query parameters, and the OpenAPI document.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace httplib {
class ContentReader;
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace spinfold::server {

struct Limits;
struct ServerContext;
struct Route;

enum class ParamType {
  integer,      // a whole number (64-bit)
  number,       // a finite double
  string,       // any text
  enumeration,  // one of `values`
  list,         // comma-separated items, each one of `values` (empty items are ignored)
};

// A query parameter's value after parsing: integer → long long, number → double, the rest → text.
using QueryValue = std::variant<long long, double, std::string>;

struct QueryParam {
  std::string name{};
  ParamType type = ParamType::string;
  std::string unit{};                         // "" when none (e.g. "pixels", "rad", "Hz")
  std::optional<double> minimum{};            // integer and number: the smallest value allowed
  std::optional<double> maximum{};            // integer and number: the largest value allowed
  bool exclusive_minimum = false;             // the minimum itself is refused: (minimum, maximum]
  std::vector<std::string> values{};          // enumeration and list: the allowed values
  std::optional<QueryValue> default_value{};  // what the handler gets when the parameter is absent
  std::string description{};                  // one line, for the OpenAPI document
};

struct RequestBody {
  std::string description{};  // what the body holds
  std::vector<std::string> content_types = {"application/json"};
  bool required = true;  // false: an empty body is allowed (the handler checks)
  nlohmann::ordered_json schema = {{"type", "object"}};  // JSON Schema of the body
};

// The query parameters of one request, parsed and checked against the route's declarations.
class Query {
 public:
  Query() = default;
  explicit Query(const std::vector<QueryParam>* declared) : declared_(declared) {}
  // The value given (or the declared default), or nullopt; asking for an undeclared name or the
  // wrong type is a programming error (std::logic_error).
  std::optional<long long> integer(std::string_view name) const;
  std::optional<double> number(std::string_view name) const;     // number, or integer as a double
  std::optional<std::string> text(std::string_view name) const;  // string, enumeration or list
  void set(const std::string& name, QueryValue value) { values_[name] = std::move(value); }

 private:
  const QueryValue* find(std::string_view name) const;
  const std::vector<QueryParam>* declared_ = nullptr;
  std::map<std::string, QueryValue, std::less<>> values_;
};

// What a handler receives: the request, its route, the {id} of the path and the parsed query.
struct Call {
  const httplib::Request& http;
  const Route& route;
  std::string id;      // the {id} path segment ("" when the path has none)
  std::string client;  // the client's address (server/http/quota.h: client_address)
  Query query;
  std::string body_text;  // read by register_routes, at most Limits::max_body_bytes (else 413)
  // The JSON body, of one of the route's content types (ApiError 400/415 otherwise).
  nlohmann::json body() const;
  bool has_body() const;
};

// Handlers only translate: parse (already done for the query), call, serialise.
using Handler = void (*)(ServerContext& server, const Call& call, httplib::Response& res);

struct Route {
  std::string method{};  // "GET", "POST", "PATCH" or "DELETE"
  std::string path{};    // OpenAPI style: "/api/v1/sessions/{id}/frame.png"
  // The OpenAPI operationId: a snake_case verb and noun (create_session, get_frame), unique and
  // stable (generated clients name their methods by it). The web assets' ids are made from their paths.
  std::string operation_id{};
  Handler handler = nullptr;
  std::string summary{};               // one line, for the OpenAPI document
  std::vector<QueryParam> query{};     // every query parameter the route takes
  std::optional<RequestBody> body{};   // nullopt: the body is ignored
  bool ignores_unknown_query = false;  // a page people open: links may carry parameters it does
                                       // not use (tracking, cache busting); the API refuses them
  std::vector<std::pair<int, std::string>> responses{};  // status → description (404, 400, 413,
                                                         // 415 and 422 are added where they apply)
};

// The router regex of an OpenAPI path: "{id}" → a session id group, the rest literal.
std::string path_regex(const std::string& path);

// The methods the table has for a path (the Allow of a 405).
std::vector<std::string> methods_of(const std::vector<Route>& routes, const std::string& path);

// The body of a request, read here rather than by httplib, at most `limit` bytes: ApiError 400
// (no Content-Length, malformed chunks) or 413 (over the limit), the connection then closed.
std::string bounded_body(const httplib::Request& req, const httplib::ContentReader& reader, std::size_t limit,
                         httplib::Response& res);

// ApiError 400 when a chunked body's bytes as they arrived are malformed (server/http/framing.h).
void refuse_malformed_chunks(const httplib::Request& req, httplib::Response& res);

// The query of a request checked against a route: unknown names, duplicates, values of the wrong
// type or out of range are ApiError 422 naming the parameter, the value and the reason.
Query parse_query(const Route& route, const httplib::Request& req);

// The JSON Schema of a query parameter's value (its type, enum or list pattern, bounds, default,
// x-unit): the OpenAPI parameter's schema, and a recording body field's of the same name.
nlohmann::ordered_json parameter_schema(const QueryParam& p);

// The OpenAPI 3.1 document of the table: every operation (its operationId, query parameters, body
// schema, answers; every error as application/problem+json of the shared Problem schema).
nlohmann::ordered_json openapi_document(const std::vector<Route>& routes);

}  // namespace spinfold::server
