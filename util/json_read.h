#pragma once
// Checked reads of JSON files written by shadowlab and read back (merge, --from; the files
// themselves through core/json_file.h). Every field is read through these, so that a missing or
// mistyped field is one line naming the file and the key ("FILE: 'kind' is missing") instead of
// nlohmann's exception text; nlohmann's get<size_t>() would also convert a float such as 1e30
// with a plain cast (undefined behaviour) and wrap large integers.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace shadowlab {

// j[key] as a whole number in [0, max]; InputError(where, …) otherwise (missing, not an
// integer, negative, too large).
inline uint64_t json_uint(const nlohmann::json& j, const char* key, uint64_t max,
                          const std::string& where) {
  if (!j.is_object() || !j.contains(key) || !(j.at(key).is_number_unsigned() || j.at(key).is_number_integer()))
    throw InputError(where, std::string("'") + key + "' is missing or not a whole number");
  const nlohmann::json& v = j.at(key);
  if (v.is_number_integer() && !v.is_number_unsigned() && v.get<int64_t>() < 0)
    throw InputError(where, std::string("'") + key + "' is negative");
  const uint64_t u = v.get<uint64_t>();
  if (u > max) throw InputError(where, std::string("'") + key + "' = " + std::to_string(u) + " is too large");
  return u;
}

// j[key], which must exist; InputError(where, "'key' is missing") otherwise.
inline const nlohmann::json& json_at(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_object()) throw InputError(where, std::string("expected an object holding '") + key + "'");
  const auto it = j.find(key);
  if (it == j.end()) throw InputError(where, std::string("'") + key + "' is missing");
  return *it;
}

inline std::string json_string(const nlohmann::json& j, const char* key, const std::string& where) {
  const nlohmann::json& v = json_at(j, key, where);
  if (!v.is_string()) throw InputError(where, std::string("'") + key + "' is not a string");
  return v.get<std::string>();
}

inline double json_number(const nlohmann::json& j, const char* key, const std::string& where) {
  const nlohmann::json& v = json_at(j, key, where);
  if (!v.is_number()) throw InputError(where, std::string("'") + key + "' is not a number");
  return v.get<double>();
}

inline bool json_bool(const nlohmann::json& j, const char* key, const std::string& where) {
  const nlohmann::json& v = json_at(j, key, where);
  if (!v.is_boolean()) throw InputError(where, std::string("'") + key + "' is not true or false");
  return v.get<bool>();
}

inline std::vector<std::string> json_strings(const nlohmann::json& j, const char* key,
                                             const std::string& where) {
  const nlohmann::json& v = json_at(j, key, where);
  std::vector<std::string> out;
  if (v.is_array())
    for (const nlohmann::json& s : v) {
      if (!s.is_string()) break;
      out.push_back(s.get<std::string>());
    }
  if (!v.is_array() || out.size() != v.size())
    throw InputError(where, std::string("'") + key + "' is not a list of strings");
  return out;
}

inline const nlohmann::json& json_array(const nlohmann::json& j, const char* key, const std::string& where) {
  const nlohmann::json& v = json_at(j, key, where);
  if (!v.is_array()) throw InputError(where, std::string("'") + key + "' is not a list");
  return v;
}

// An nlohmann exception's text without its "[json.exception.type_error.302] " tag: the
// last guard of a reader whose fields the helpers above did not all cover.
inline std::string json_error_text(const nlohmann::json::exception& e) {
  const std::string s = e.what();
  const size_t close = s.find("] ");
  return s.rfind("[json.exception.", 0) == 0 && close != std::string::npos ? s.substr(close + 2) : s;
}

// The first place where two JSON values differ, as a path ("scenes/0/width"; "" when the values
// themselves differ), so that a message names the one field instead of dumping both values.
inline std::string json_first_difference(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.is_object() && b.is_object()) {
    for (auto it = a.begin(); it != a.end(); ++it) {
      if (!b.contains(it.key())) return it.key();
      if (b.at(it.key()) != it.value()) {
        const std::string sub = json_first_difference(it.value(), b.at(it.key()));
        return sub.empty() ? it.key() : it.key() + "/" + sub;
      }
    }
    for (auto it = b.begin(); it != b.end(); ++it)
      if (!a.contains(it.key())) return it.key();
    return "";
  }
  if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i] != b[i]) {
        const std::string sub = json_first_difference(a[i], b[i]);
        return std::to_string(i) + (sub.empty() ? "" : "/" + sub);
      }
  }
  return "";
}

// A JSON value as short text for a message: its dump, cut to `max` characters with "...".
inline std::string json_short_text(const nlohmann::json& v, size_t max = 40) {
  const std::string s = v.dump();
  return s.size() <= max ? s : s.substr(0, max - 3) + "...";
}

// "provenance 'scenes/0/width' differs from OTHER's (320 vs 640)": the first differing field of
// two provenance objects and its two values, each cut short.
inline std::string provenance_difference(const nlohmann::json& mine, const nlohmann::json& theirs,
                                         const std::string& other_path) {
  const std::string field = json_first_difference(mine, theirs);
  auto value = [&](const nlohmann::json& p) {
    if (field.empty()) return std::string("missing");
    try {
      const nlohmann::json::json_pointer ptr("/" + field);
      return p.contains(ptr) ? json_short_text(p.at(ptr)) : std::string("missing");
    } catch (const nlohmann::json::exception&) {
      return std::string("?");  // a key that is no valid pointer token ('~')
    }
  };
  return "provenance '" + field + "' differs from " + other_path + "'s (" + value(mine) + " vs " +
         value(theirs) + ")";
}

}  // namespace shadowlab
