// Errors as application/problem+json and the reading of request bodies (server/http/problem.h), called
// directly on httplib's request and response objects, without a server.
#include "server/http/problem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

// After Eigen (through engine/validation.h): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

namespace spinfold::server {
namespace {

using nlohmann::json;

// The ApiError a call throws; fails the test when it throws nothing.
template <typename Call>
ApiError thrown_by(Call call) {
  try {
    call();
  } catch (const ApiError& e) {
    return e;
  }
  ADD_FAILURE() << "no ApiError thrown";
  return {};
}

httplib::Request request_of_type(const std::string& content_type) {
  httplib::Request req;
  if (!content_type.empty()) req.set_header("Content-Type", content_type);
  return req;
}

// RFC 9457's members in order, with the errors array naming field, value and reason.
TEST(Problem, SendErrorWritesProblemJson) {
  httplib::Response res;
  send_error(
      res,
      ApiError{422, "Invalid value", {{"body.mass", "-1", "must be > 0"}, {"dt", "", "is missing"}}, ""});
  EXPECT_EQ(res.status, 422);
  EXPECT_EQ(res.get_header_value("Content-Type"), "application/problem+json");
  EXPECT_FALSE(res.has_header("Retry-After"));
  const nlohmann::ordered_json body = nlohmann::ordered_json::parse(res.body);
  std::vector<std::string> keys;
  for (const auto& [key, value] : body.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"type", "title", "status", "detail", "errors"}));
  EXPECT_EQ(body["type"], "about:blank");
  EXPECT_EQ(body["title"], "Invalid value");
  EXPECT_EQ(body["status"], 422);
  EXPECT_EQ(body["detail"], "body.mass: must be > 0 (got -1); dt: is missing");
  ASSERT_EQ(body["errors"].size(), 2u);
  EXPECT_EQ(body["errors"][0], (json{{"field", "body.mass"}, {"value", "-1"}, {"reason", "must be > 0"}}));
}

TEST(Problem, RetryAfterIsSentWhenGiven) {
  httplib::Response res;
  send_error(res, ApiError{429, "Too many requests", {}, "7"});
  EXPECT_EQ(res.status, 429);
  EXPECT_EQ(res.get_header_value("Retry-After"), "7");
  EXPECT_EQ(json::parse(res.body)["errors"], json::array());
}

// A value quoted back that is not UTF-8 is replaced, not a failed answer.
TEST(Problem, InvalidUtf8InAValueStillGivesJson) {
  httplib::Response res;
  send_error(res, bad(400, "Malformed request", "name",
                      std::string("a\xff"
                                  "b"),
                      "is not UTF-8"));
  const json body = json::parse(res.body);
  EXPECT_EQ(body["errors"][0]["value"],
            "a\xEF\xBF\xBD"
            "b");  // U+FFFD
}

// The detail cuts a long value to 80 bytes; the errors entry keeps it whole.
TEST(Problem, DetailCutsLongValues) {
  const std::string long_value(200, 'x');
  EXPECT_EQ(problem_detail({{"f", long_value, "is too long"}}),
            "f: is too long (got " + std::string(80, 'x') + "…)");
  EXPECT_EQ(problem_detail({{"", "", "the body is empty"}}), "the body is empty");
  EXPECT_EQ(problem_detail({}), "");
}

TEST(Problem, UnknownSessionIsOne404NamingTheId) {
  const ApiError e = unknown_session("abc");
  EXPECT_EQ(e.status, 404);
  EXPECT_EQ(e.title, "Unknown session");
  ASSERT_EQ(e.errors.size(), 1u);
  EXPECT_EQ(e.errors[0].field, "id");
  EXPECT_EQ(e.errors[0].value, "abc");
}

// The media type is compared without parameters, spaces or case; anything else is 415 naming
// what is accepted.
TEST(Problem, ParseBodyChecksTheMediaType) {
  const std::vector<std::string> types{"application/json", "application/merge-patch+json"};
  EXPECT_EQ(parse_body(request_of_type("Application/JSON ; charset=utf-8"), R"({"a": 1})", types)["a"], 1);
  EXPECT_EQ(parse_body(request_of_type("application/merge-patch+json"), "{}", types), json::object());
  const ApiError wrong = thrown_by([&] { parse_body(request_of_type("text/plain"), "{}", types); });
  EXPECT_EQ(wrong.status, 415);
  EXPECT_EQ(wrong.errors[0].reason, "must be application/json or application/merge-patch+json");
  const ApiError missing = thrown_by([&] { parse_body(request_of_type(""), "{}", types); });
  EXPECT_EQ(missing.status, 415);
  EXPECT_TRUE(missing.errors[0].reason.starts_with("is missing")) << missing.errors[0].reason;
}

// An empty, malformed, trailing or NUL-cut body is 400 with the reason of the strict reading.
TEST(Problem, ParseBodyRefusesWhatIsNotOneJsonValue) {
  const httplib::Request req = request_of_type("application/json");
  const std::vector<std::string> types{"application/json"};
  for (const std::string& body :
       {std::string(""), std::string("{"), std::string("{} {}"), std::string("{}") + '\0' + "x",
        std::string(40, '[') + std::string(40, ']')}) {
    const ApiError e = thrown_by([&] { parse_body(req, body, types); });
    EXPECT_EQ(e.status, 400) << body;
    EXPECT_EQ(e.title, "Malformed request") << body;
  }
}

TEST(Problem, RequireObjectRefusesOtherValues) {
  EXPECT_NO_THROW(require_object(json::object()));
  for (const json& value : {json::array(), json(1), json("s"), json(nullptr)})
    EXPECT_EQ(thrown_by([&] { require_object(value); }).status, 400) << value;
}

// Every unknown key is named in one 422, with the known ones listed.
TEST(Problem, UnknownKeysAreEachNamed) {
  EXPECT_NO_THROW(refuse_unknown_keys(json{{"dt", 1}}, {"dt", "t"}));
  const ApiError e = thrown_by([] {
    refuse_unknown_keys(json{{"dt", 1}, {"x", 2}, {"y", "z"}}, {"dt", "t"});
  });
  EXPECT_EQ(e.status, 422);
  ASSERT_EQ(e.errors.size(), 2u);
  EXPECT_EQ(e.errors[0].field, "x");
  EXPECT_EQ(e.errors[0].value, "2");
  EXPECT_EQ(e.errors[0].reason, "is not a known field (dt, t)");
  EXPECT_EQ(e.errors[1].field, "y");
}

TEST(Problem, NumberFieldIsFiniteAndNamed) {
  EXPECT_EQ(number_field(json{{"dt", 0.25}}, "dt"), 0.25);
  EXPECT_EQ(number_field(json{{"n", 3}}, "n"), 3.0);
  const ApiError text = thrown_by([] { number_field(json{{"dt", "0.1"}}, "dt"); });
  EXPECT_EQ(text.status, 422);
  EXPECT_EQ(text.errors[0].field, "dt");
  EXPECT_EQ(text.errors[0].reason, "must be a number");
  // nlohmann keeps an infinity it was given in code (JSON text cannot carry one).
  const ApiError infinite = thrown_by([] {
    number_field(json{{"dt", std::numeric_limits<double>::infinity()}}, "dt");
  });
  EXPECT_EQ(infinite.errors[0].reason, "must be finite");
}

}  // namespace
}  // namespace spinfold::server
