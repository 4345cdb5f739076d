// The strict JSON reading every input goes through (codec/json_text.h): exactly one value, no NUL
// byte, a bounded depth, and each refusal says why.
#include "codec/json_text.h"

#include <gtest/gtest.h>

#include <string>

#include "codec/scene_json.h"

namespace spinfold {
namespace {

// Exactly one JSON value: nlohmann-json alone reads a NUL byte as the end of its input, so the
// text after one would be ignored; a second value or trailing text is an error too.
TEST(JsonText, OnlyExactlyOneValue) {
  EXPECT_EQ(parse_json_text(" {\"a\": 1}\r\n\t ")["a"], 1);
  for (const std::string& text :
       {std::string("{\"a\": 1}") + '\0' + "garbage", std::string("{\"a\": 1}") + '\0',
        '\0' + std::string("{}"), std::string("{\"a\": \"x") + '\0' + "y\"}", std::string("{\"a\": 1} x"),
        std::string("{\"a\": 1}{\"a\": 2}"), std::string("1 2"), std::string(""),
        std::string(40, '[') + std::string(40, ']')})
    EXPECT_THROW(parse_json_text(text), JsonTextError) << text;
  try {
    parse_json_text(std::string("{}") + '\0');
  } catch (const JsonTextError& e) {
    EXPECT_NE(std::string(e.what()).find("NUL byte at byte 2"), std::string::npos) << e.what();
  }
  const SceneParse p = parse_scene_text(std::string(R"({"body": {"mass": 2.5}})") + '\0' + "garbage");
  EXPECT_FALSE(p.scene);
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_NE(p.errors[0].reason.find("NUL"), std::string::npos);
}

// The depth bound counts as nlohmann-json does, the outermost value at depth 0: kMaxJsonDepth + 1
// nested arrays are read, one more is refused as too deep (not as malformed), so a client can tell
// the two apart.
TEST(JsonText, DepthBoundIsKMaxJsonDepthBelowTheOutermostValue) {
  const auto nested = [](int levels) { return std::string(levels, '[') + std::string(levels, ']'); };
  EXPECT_NO_THROW(parse_json_text(nested(kMaxJsonDepth + 1)));
  try {
    parse_json_text(nested(kMaxJsonDepth + 2));
    ADD_FAILURE() << kMaxJsonDepth + 2 << " nested arrays were accepted";
  } catch (const JsonTextError& e) {
    EXPECT_NE(std::string(e.what()).find("nested deeper than 32 levels"), std::string::npos) << e.what();
  }
}

// Malformed text is refused with the parser's reason behind one prefix, and whitespace alone is
// no value.
TEST(JsonText, MalformedTextNamesItself) {
  for (const std::string text : {"{", "{\"a\": }", "[1,]", "tru", "   \n", "{'a': 1}"}) {
    try {
      parse_json_text(text);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const JsonTextError& e) {
      EXPECT_TRUE(std::string(e.what()).starts_with("malformed JSON: ")) << e.what();
    }
  }
}

// A NUL escaped inside a string is JSON (\u0000) and kept; only a raw NUL byte is refused.
TEST(JsonText, EscapedNulIsAValueRawNulIsNot) {
  const nlohmann::json value = parse_json_text(R"({"name": "a\u0000b"})");
  EXPECT_EQ(value["name"].get<std::string>(), std::string("a\0b", 3));
  EXPECT_THROW(parse_json_text(std::string("{\"name\": \"a") + '\0' + "b\"}"), JsonTextError);
}

// Every JSON type reads back as itself, numbers exactly.
TEST(JsonText, ScalarsAndContainersReadBackExactly) {
  const nlohmann::json v = parse_json_text(R"([1, -2.5, 1e-300, "s", true, null, {"k": [ ]}])");
  ASSERT_EQ(v.size(), 7u);
  EXPECT_EQ(v[0].get<int>(), 1);
  EXPECT_EQ(v[1].get<double>(), -2.5);
  EXPECT_EQ(v[2].get<double>(), 1e-300);
  EXPECT_EQ(v[3], "s");
  EXPECT_EQ(v[4], true);
  EXPECT_TRUE(v[5].is_null());
  EXPECT_TRUE(v[6]["k"].is_array() && v[6]["k"].empty());
}

// A key repeated in one object is refused naming its path, in either order (nlohmann-json alone
// keeps the last: `{"mass": -1, "mass": 1}` read as mass 1); the same key in two objects is fine.
TEST(JsonText, ARepeatedKeyIsRefusedNamingItsPath) {
  const std::pair<std::string, std::string> cases[] = {
      {R"({"body": {"mass": -1, "mass": 1}})", "body.mass"},
      {R"({"body": {"mass": 1, "mass": -1}})", "body.mass"},
      {R"({"a": 1, "a": 1})", "a"},
      {R"({"companions": [{"label": "x"}, {"label": "y", "initial": {"r": 1, "phi": 0, "r": 2}}]})",
       "companions[1].initial.r"},
      {R"([[1, 2], {"k": [], "k": {}}])", "[1].k"},
  };
  for (const auto& [text, path] : cases) {
    try {
      parse_json_text(text);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const JsonTextError& e) {
      EXPECT_EQ(e.field, path) << text;
      EXPECT_NE(std::string(e.what()).find("appears twice"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(parse_json_text(R"({"a": {"k": 1}, "b": {"k": 2}, "c": [{"k": 1}, {"k": 2}], "k": 0})"));
  const SceneParse p = parse_scene_text(R"({"body": {"mass": -1, "mass": 1}})");
  EXPECT_FALSE(p.scene);
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(p.errors[0].field, "body.mass");
}

}  // namespace
}  // namespace spinfold
