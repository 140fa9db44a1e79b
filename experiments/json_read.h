#pragma once
// Checked reads of numbers from JSON files written by shadowlab and read back (merge, --from;
// the files themselves through core/json_file.h): nlohmann's get<size_t>() converts a float
// such as 1e30 with a plain cast (undefined behaviour) and wraps large integers, so counts and
// indices are read through this instead.
#include <cstdint>
#include <string>

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

}  // namespace shadowlab
