#pragma once
// The environment variables the programs read, checked by the rules of the flags they stand for
// before any work (run_main): SHADOWLAB_THREADS is --threads' integer in [1, 1024] (strict:
// no spaces, no '+'), SHADOWLAB_ISA is "scalar", "avx2" or "avx512" and no wider than the CPU
// runs, SHADOWLAB_SCALAR is 0 or 1. An empty value is the variable unset, as the readers treat it.
// A bad value is an InputError naming the variable (one line, exit code 2) instead of being
// ignored or read as a number it only starts with.
#include <string>

namespace shadowlab {

// Throws InputError("SHADOWLAB_X", reason) for the first variable whose value breaks its rule.
void check_environment();

// One variable's check on a value (for tests); throws like check_environment.
void check_environment_value(const std::string& name, const std::string& value);

}  // namespace shadowlab
