#include "core/json_file.h"

#include "core/json_check.h"

namespace shadowlab {

nlohmann::json read_json_file(const std::string& path, const InputLimit& limit) {
  const std::string text = read_input_file(path, limit);
  check_json_text(text, path);
  return nlohmann::json::parse(text);  // the same parser check_json_text ran: it cannot throw
}

}  // namespace shadowlab
