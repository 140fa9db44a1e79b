#include "core/error.h"

namespace shadowlab {

void check_failed(const char* file, int line, const std::string& message) {
  std::fprintf(stderr, "%s:%d: %s\n", file, line, message.c_str());
  std::abort();
}

}  // namespace shadowlab
