#include "lab/environment.h"

#include <cstdlib>

#include "core/error.h"
#include "core/parse_number.h"

namespace shadowlab {

void check_environment_value(const std::string& name, const std::string& value) {
  if (value.empty()) return;
  if (name == "SHADOWLAB_THREADS") {
    long n = 0;
    if (!parse_long(value, n)) throw InputError(name, "expected an integer, got '" + value + "'");
    if (n < 1 || n > 1024) throw InputError(name, value + " is outside [1, 1024]");
  } else if (name == "SHADOWLAB_ISA") {
    if (value != "avx2")
      throw InputError(name, "expected avx2 (the AVX2 kernels; unset it for the widest the CPU has), got '" +
                                 value + "'");
  } else if (name == "SHADOWLAB_SCALAR") {
    if (value != "0" && value != "1") throw InputError(name, "expected 0 or 1, got '" + value + "'");
  }
}

void check_environment() {
  for (const char* name : {"SHADOWLAB_THREADS", "SHADOWLAB_ISA", "SHADOWLAB_SCALAR"})
    if (const char* v = std::getenv(name)) check_environment_value(name, v);
}

}  // namespace shadowlab
