#pragma once
// The two error channels (style.md #8): InputError for bad external input (file, flag, scene
// value) — caught in main, printed as one line, exit code 2 — and SL_CHECK for programmer
// invariants, which aborts with both values printed.
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace shadowlab {

// Bad external input. `where` names the file or flag, `reason` says what is wrong.
struct InputError : std::runtime_error {
  InputError(const std::string& where, const std::string& reason)
      : std::runtime_error(where + ": " + reason), where(where), reason(reason) {}
  std::string where;
  std::string reason;
};

[[noreturn]] void check_failed(const char* file, int line, const std::string& message);

}  // namespace shadowlab

// Programmer invariant: SL_CHECK(cond) or SL_CHECK_EQ(a, b); prints the values and aborts.
#define SL_CHECK(cond)                                                            \
  do {                                                                            \
    if (!(cond)) ::shadowlab::check_failed(__FILE__, __LINE__, "CHECK(" #cond ")"); \
  } while (0)
#define SL_CHECK_OP(a, op, b)                                                       \
  do {                                                                              \
    const auto& sl_va = (a);                                                        \
    const auto& sl_vb = (b);                                                        \
    if (!(sl_va op sl_vb)) {                                                        \
      std::ostringstream sl_os;                                                     \
      sl_os << "CHECK(" #a " " #op " " #b ") with " << sl_va << " vs " << sl_vb;    \
      ::shadowlab::check_failed(__FILE__, __LINE__, sl_os.str());                   \
    }                                                                               \
  } while (0)
#define SL_CHECK_EQ(a, b) SL_CHECK_OP(a, ==, b)
#define SL_CHECK_LT(a, b) SL_CHECK_OP(a, <, b)
#define SL_CHECK_LE(a, b) SL_CHECK_OP(a, <=, b)
