#include "core/json_check.h"

#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace shadowlab {
namespace {

// A SAX consumer that builds nothing: it follows the nesting (one frame per open array or
// object, at most kMaxJsonDepth) and the keys of each open object.
class JsonChecker {
 public:
  using json = nlohmann::json;
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  std::string error;  // the reason the text is refused; empty when accepted

  bool null() { return value(); }
  bool boolean(bool) { return value(); }
  bool number_integer(number_integer_t) { return value(); }
  bool number_unsigned(number_unsigned_t) { return value(); }
  bool number_float(number_float_t, const string_t&) { return value(); }
  bool string(string_t&) { return value(); }
  bool binary(binary_t&) { return value(); }
  bool start_object(std::size_t) { return open(true); }
  bool start_array(std::size_t) { return open(false); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(string_t& k) {
    Frame& f = frames_.back();
    f.key = k;
    f.has_key = true;
    if (!f.keys.insert(k).second) {
      error = path() + ": duplicate key in a JSON object (each key may appear once)";
      return false;
    }
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    if (e.id == 406)  // a number beyond double's range
      error = "a JSON number is out of range (beyond \u00b11.8e308)";
    else
      error = "JSON syntax error at byte " + std::to_string(position);
    return false;
  }

 private:
  struct Frame {
    bool object = false;
    size_t index = 0;  // elements seen so far (arrays)
    std::string key;   // the latest key (objects)
    bool has_key = false;
    std::set<std::string> keys;
  };

  bool value() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
    return true;
  }
  bool open(bool object) {
    value();
    if (frames_.size() >= size_t(kMaxJsonDepth)) {
      error = "JSON nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels at " + path(4) +
              "...";
      return false;
    }
    frames_.push_back(Frame{});
    frames_.back().object = object;
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
  // A key as one short line: control characters as '?', at most 40 bytes.
  static std::string printable(const std::string& key) {
    std::string out = key.substr(0, 40);
    for (char& c : out)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return key.size() > 40 ? out + "..." : out;
  }
  // "models[2].file": where the parser is, for messages (at most kMaxJsonDepth parts).
  // With max_parts, only the first parts (the depth message: the rest repeats).
  std::string path(size_t max_parts = kMaxJsonDepth) const {
    std::string p;
    for (size_t i = 0; i < frames_.size() && i < max_parts; ++i) {
      const Frame& f = frames_[i];
      if (f.object && f.has_key) {
        if (!p.empty()) p += '.';
        p += printable(f.key);
      } else if (!f.object && f.index > 0) {
        p += '[';
        p += std::to_string(f.index - 1);
        p += ']';
      }
    }
    return p;
  }

  std::vector<Frame> frames_;
};

}  // namespace

void check_json_text(const char* text, size_t size, const std::string& where) {
  JsonChecker checker;
  bool ok = false;
  try {
    ok = nlohmann::json::sax_parse(text, text + size, &checker, nlohmann::json::input_format_t::json,
                                   /*strict=*/true, /*ignore_comments=*/false);
  } catch (const nlohmann::json::exception&) {
    ok = false;  // the parser reports through parse_error; nothing else throws
    if (checker.error.empty()) checker.error = "is not valid JSON";
  }
  if (!ok) throw InputError(where, checker.error.empty() ? "is not valid JSON" : checker.error);
}

}  // namespace shadowlab
