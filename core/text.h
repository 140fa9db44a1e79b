#pragma once
// Small text helpers shared by the loaders.
#include <cctype>
#include <string>

namespace shadowlab {

// s with ASCII letters in lower case (file extensions, keywords); other bytes unchanged.
inline std::string ascii_lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace shadowlab
