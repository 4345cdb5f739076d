// Errors as application/problem+json (RFC 9457), mapped in one place, and the JSON bodies of
// requests.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/validation.h"

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace spinfold::server {

// An error a handler reports: written as problem+json by send_error.
struct ApiError {
  int status;
  std::string title;
  std::vector<FieldError> errors;  // each names the field, the value and the reason
  std::string retry_after;         // seconds, for 429/503
};

// An error about one field.
ApiError bad(int status, const std::string& title, const std::string& field, const std::string& value,
             const std::string& reason);

// The 404 of an unknown session id: the same answer on every route.
ApiError unknown_session(const std::string& id);

// The problem's `detail`: each error as "field: reason (got value)", joined by "; ".
std::string problem_detail(const std::vector<FieldError>& errors);

// Writes the problem+json answer (and Retry-After when given).
void send_error(httplib::Response& res, const ApiError& e);

// The JSON body of a request: its Content-Type one of `content_types` (parameters such as charset
// aside), not empty, well-formed, nested at most kMaxJsonDepth deep; ApiError 400/415 otherwise.
nlohmann::json parse_body(const httplib::Request& req, const std::string& body,
                          const std::vector<std::string>& content_types);

// The body must be a JSON object (400 otherwise).
void require_object(const nlohmann::json& body);
// Keys of an object outside `known` are 422, each named as an unknown field.
void refuse_unknown_keys(const nlohmann::json& body, const std::vector<std::string>& known);

// A finite number at `key` of an object (422 naming the key otherwise).
double number_field(const nlohmann::json& body, const char* key);

}  // namespace spinfold::server
