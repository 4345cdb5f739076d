#include "server/http/problem.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "codec/json_text.h"
#include "codec/scene_json.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// Values quoted in a detail are cut to this many bytes (the `errors` entry keeps them whole).
constexpr std::size_t kDetailValueBytes = 80;

std::string joined(const std::vector<std::string>& items, const std::string& last) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  return text;
}

// "application/json; charset=utf-8" → "application/json".
std::string media_type(const std::string& header) {
  std::string type = header.substr(0, header.find(';'));
  type.erase(std::remove_if(type.begin(), type.end(), [](unsigned char c) { return std::isspace(c); }),
             type.end());
  std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return std::tolower(c); });
  return type;
}

}  // namespace

ApiError bad(int status, const std::string& title, const std::string& field, const std::string& value,
             const std::string& reason) {
  return {status, title, {{field, value, reason}}, ""};
}

ApiError unknown_session(const std::string& id) {
  return bad(404, "Unknown session", "id", id, "no session with this id (it may have expired)");
}

std::string problem_detail(const std::vector<FieldError>& errors) {
  std::string detail;
  for (const FieldError& f : errors) {
    if (!detail.empty()) detail += "; ";
    if (!f.field.empty()) detail += f.field + ": ";
    detail += f.reason;
    if (!f.value.empty())
      detail += " (got " +
                (f.value.size() > kDetailValueBytes ? f.value.substr(0, kDetailValueBytes) + "…" : f.value) +
                ")";
  }
  return detail;
}

void send_error(httplib::Response& res, const ApiError& e) {
  ordered_json body{{"type", "about:blank"}, {"title", e.title}, {"status", e.status}};
  json errors = json::array();
  for (const FieldError& f : e.errors)
    errors.push_back({{"field", f.field}, {"value", f.value}, {"reason", f.reason}});
  body["detail"] = problem_detail(e.errors);
  body["errors"] = errors;
  res.status = e.status;
  if (!e.retry_after.empty()) res.set_header("Retry-After", e.retry_after);
  // The values quoted back may hold bytes that are not UTF-8 (a malformed body, a header, a value
  // cut short): they are replaced (U+FFFD) rather than failing the answer.
  res.body = body.dump(-1, ' ', false, json::error_handler_t::replace);
  res.set_header("Content-Type", "application/problem+json");
}

json parse_body(const httplib::Request& req, const std::string& body,
                const std::vector<std::string>& content_types) {
  const std::string header = req.get_header_value("Content-Type");
  if (std::find(content_types.begin(), content_types.end(), media_type(header)) == content_types.end())
    throw bad(415, "Unsupported media type", "Content-Type", header,
              (header.empty() ? "is missing: must be " : "must be ") + joined(content_types, " or "));
  if (body.empty())
    throw bad(400, "Malformed request", "", "", "the body is empty: a JSON object is expected");
  try {
    return parse_json_text(body);
  } catch (const JsonTextError& e) {
    if (!e.field.empty()) throw bad(422, "Invalid value", e.field, "", e.what());  // a repeated key
    throw bad(400, "Malformed request", "", "", e.what());
  }
}

void require_object(const json& body) {
  if (!body.is_object())
    throw bad(400, "Malformed request", "", body.dump(), "the body must be a JSON object");
}

void refuse_unknown_keys(const json& body, const std::vector<std::string>& known) {
  std::vector<FieldError> errors;
  for (const auto& [key, value] : body.items())
    if (std::find(known.begin(), known.end(), key) == known.end())
      errors.push_back({key, value.dump(), "is not a known field (" + joined(known, ", ") + ")"});
  if (!errors.empty()) throw ApiError{422, "Invalid value", errors, ""};
}

double number_field(const json& body, const char* key) {
  const json& v = body.at(key);
  if (!v.is_number()) throw bad(422, "Invalid value", key, v.dump(), "must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw bad(422, "Invalid value", key, v.dump(), "must be finite");
  return x;
}

}  // namespace spinfold::server
