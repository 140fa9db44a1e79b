// check_json_text (core/json_check.h): nesting up to kMaxJsonDepth and no deeper, counted on
// arrays and objects and not on brackets inside strings; each key once per object, compared
// after unescaping; syntax errors by byte. The texts are built here, so each expected depth is
// known by construction.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/json_check.h"

namespace shadowlab {
namespace json_check_test {

// The reason check_json_text gives for `text`; empty when it accepts it.
std::string refusal(const std::string& text) {
  try {
    check_json_text(text, "t.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "t.json");
    return e.reason;
  }
  return "";
}

std::string nested_arrays(int depth) { return std::string(size_t(depth), '[') + std::string(size_t(depth), ']'); }

std::string nested_objects(int depth) {
  std::string s;
  for (int i = 0; i < depth; ++i) s += i + 1 < depth ? "{\"k\":" : "{";
  return s + std::string(size_t(depth), '}');
}

TEST(JsonCheck, NestingUpToTheLimitIsAccepted) {
  EXPECT_EQ(refusal(nested_arrays(kMaxJsonDepth)), "");
  EXPECT_EQ(refusal(nested_objects(kMaxJsonDepth)), "");
  EXPECT_EQ(refusal("{\"a\": " + nested_arrays(kMaxJsonDepth - 1) + "}"), "");
}

TEST(JsonCheck, NestingBeyondTheLimitIsRefused) {
  EXPECT_NE(refusal(nested_arrays(kMaxJsonDepth + 1)).find("JSON nesting deeper than 64 levels"), std::string::npos);
  EXPECT_NE(refusal(nested_objects(kMaxJsonDepth + 1)).find("JSON nesting deeper than 64 levels"), std::string::npos);
  // 20,000 levels (a recursive parser's stack overflow): refused the same way, in one line.
  const std::string deep = refusal("{\"extras\": " + nested_arrays(20000) + "}");
  EXPECT_EQ(deep.rfind("JSON nesting deeper than 64 levels at extras[0][0]", 0), 0u) << deep;
  EXPECT_EQ(deep.find('\n'), std::string::npos);
  // Unclosed: the depth is refused before the missing brackets are noticed.
  EXPECT_NE(refusal(std::string(20000, '[')).find("nesting"), std::string::npos);
}

TEST(JsonCheck, BracketsInStringsAreNotNesting) {
  const std::string brackets(1000, '[');
  EXPECT_EQ(refusal("[\"" + brackets + "\", \"\\\"[{\"]"), "");
  EXPECT_EQ(refusal("{\"" + brackets + "\": 1}"), "");
}

TEST(JsonCheck, DuplicateKeysAreRefusedWithTheirPath) {
  EXPECT_EQ(refusal(R"({"base": "plane", "base": "default"})"), "base: duplicate key in a JSON object (each key may appear once)");
  // The same key after unescaping ("a" and "\u0061").
  EXPECT_EQ(refusal(R"({"a": 1, "\u0061": 2})"), "a: duplicate key in a JSON object (each key may appear once)");
  EXPECT_EQ(refusal(R"({"models": [{"file": "a"}, {"file": "b", "file": "c"}]})"),
            "models[1].file: duplicate key in a JSON object (each key may appear once)");
  // The same key in sibling or nested objects is not a duplicate.
  EXPECT_EQ(refusal(R"({"a": {"a": 1}, "b": [{"a": 1}, {"a": 2}]})"), "");
  // A key with a newline is shown on one line.
  EXPECT_EQ(refusal("{\"x\\ny\": 1, \"x\\ny\": 2}").find('\n'), std::string::npos);
}

TEST(JsonCheck, SyntaxErrorsAndHugeNumbers) {
  EXPECT_EQ(refusal(R"({"a": 1,)"), "JSON syntax error at byte 9");
  EXPECT_EQ(refusal(""), "JSON syntax error at byte 1");
  EXPECT_EQ(refusal("[1] [2]"), "JSON syntax error at byte 5");
  EXPECT_EQ(refusal("[1e400]"), "a JSON number is out of range (beyond \u00b11.8e308)");
  EXPECT_EQ(refusal("[1, /* no comments */ 2]").rfind("JSON syntax error", 0), 0u);
}

}  // namespace json_check_test
}  // namespace shadowlab
