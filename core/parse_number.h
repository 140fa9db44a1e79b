#pragma once
// Whole-string number parsing shared by flags, specs and slides. Strict: decimal only, an
// optional leading '-', no '+', no spaces, no hex, no "inf"/"nan"; false on empty input,
// trailing characters, overflow, or (for doubles) a non-finite value.
#include <string>

namespace shadowlab {

bool parse_double(const std::string& s, double& out);
bool parse_long(const std::string& s, long& out);
// Shortest readable text of a number for messages: "0", "1e+06", "0.25", "10000".
std::string number_text(double v);

}  // namespace shadowlab
