#include "lab/environment.h"

#include <cstdlib>

#include "core/error.h"
#include "core/isa.h"
#include "core/parse_number.h"

namespace shadowlab {

void check_environment_value(const std::string& name, const std::string& value) {
  if (value.empty()) return;
  if (name == "SHADOWLAB_THREADS") {
    long n = 0;
    if (!parse_long(value, n)) throw InputError(name, "expected an integer, got '" + value + "'");
    if (n < 1 || n > 1024) throw InputError(name, value + " is outside [1, 1024]");
  } else if (name == "SHADOWLAB_ISA") {
    Isa want = Isa::scalar;
    if (value == "avx2")
      want = Isa::avx2;
    else if (value == "avx512")
      want = Isa::avx512;
    else if (value != "scalar")
      throw InputError(name, "expected scalar, avx2 or avx512 (the widest kernel tables to use; unset: "
                             "the widest the CPU runs), got '" + value + "'");
    if (want > cpu_isa())
      throw InputError(name, value + ": this CPU runs at most " + isa_name(cpu_isa()) +
                                 ", so those kernels cannot be measured or tested here");
  } else if (name == "SHADOWLAB_SCALAR") {
    if (value != "0" && value != "1") throw InputError(name, "expected 0 or 1, got '" + value + "'");
  }
}

void check_environment() {
  for (const char* name : {"SHADOWLAB_THREADS", "SHADOWLAB_ISA", "SHADOWLAB_SCALAR"})
    if (const char* v = std::getenv(name)) check_environment_value(name, v);
}

}  // namespace shadowlab
