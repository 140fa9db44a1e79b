#pragma once
// Paths the tests need: the source tree, the build tree and the assets.
#include <string>

namespace shadowlab::test {

// Absolute path of a file inside the source tree, e.g. source_path("tests/golden/x.exr").
std::string source_path(const std::string& relative);
// Absolute path of a file inside the build tree (scratch output of tests goes there).
std::string binary_path(const std::string& relative);
// The repository's assets/ folder (core/assets.h: assets_dir()).
std::string assets_dir();

}  // namespace shadowlab::test
