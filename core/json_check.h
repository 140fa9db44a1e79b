#pragma once
// The checks every JSON text passes before a parser that builds a document sees it (nlohmann's
// DOM, tinygltf): its syntax, its nesting depth and its keys. One streaming pass without
// recursion (nlohmann's SAX parser keeps its state in a bit stack), so a text of any depth is
// checked in bounded stack; the parsers after it recurse once per level (tinygltf's conversion
// of "extras", a document's destruction), which kMaxJsonDepth bounds.
#include <cstddef>
#include <string>

namespace shadowlab {

// The deepest nesting of arrays and objects accepted (the outermost object is level 1). The
// formats read here need under 10 (a glTF node's extras, a scene file's models, a result's
// rows); 64 leaves room for any application data in a glTF "extras" while keeping the
// recursive parsers' stack use small (a few KB per level).
constexpr int kMaxJsonDepth = 64;

// Throws InputError(where, reason) unless `text` is one JSON value (RFC 8259, no comments)
// nested at most kMaxJsonDepth deep whose objects each name every key once. Reasons:
// "JSON syntax error at byte N", "a JSON number is out of range (beyond ±1.8e308)",
// "JSON nesting deeper than 64 levels at byte N", "<key path>: duplicate key in a JSON object".
void check_json_text(const char* text, size_t size, const std::string& where);
inline void check_json_text(const std::string& text, const std::string& where) {
  check_json_text(text.data(), text.size(), where);
}

}  // namespace shadowlab
