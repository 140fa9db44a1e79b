#include "experiments/json_read.h"

#include "core/input_file.h"
#include "core/json_check.h"

namespace shadowlab {

nlohmann::json read_result_json(const std::string& path) {
  const std::string text = read_input_file(path, kResultFileLimit);
  check_json_text(text, path);
  return nlohmann::json::parse(text);  // cannot fail: check_json_text ran the same parser
}

}  // namespace shadowlab
