#include "core/parse_number.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace shadowlab {

bool parse_double(const std::string& s, double& out) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool parse_long(const std::string& s, long& out) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno == ERANGE) return false;
  out = v;
  return true;
}

}  // namespace shadowlab
