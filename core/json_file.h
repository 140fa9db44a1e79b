#pragma once
// A JSON document read from a file: the file through read_input_file (a regular file within
// `limit`), its text through check_json_text (syntax, nesting depth, no duplicate keys), then
// nlohmann's parser, which cannot fail after those checks. Scene files, --from and merge inputs
// are read this way.
#include <string>

#include <nlohmann/json.hpp>

#include "core/input_file.h"

namespace shadowlab {

// Throws InputError naming `path` (core/input_file.h, core/json_check.h give the reasons).
nlohmann::json read_json_file(const std::string& path, const InputLimit& limit);

}  // namespace shadowlab
