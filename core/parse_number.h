#pragma once
// Whole-string number parsing shared by flags and technique specs: false on empty input,
// trailing characters, overflow, or (for doubles) a non-finite value.
#include <string>

namespace shadowlab {

bool parse_double(const std::string& s, double& out);
bool parse_long(const std::string& s, long& out);

}  // namespace shadowlab
