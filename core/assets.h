#pragma once
// The model assets the built-in scenes and the tests read (the Stanford bunny, the palm tree, the
// plants, the benchmark room's OBJ): the repository's own assets/ folder (docs/assets.md lists
// them with their sources and licences). Nothing outside the repository is looked at.
#include <string>

namespace shadowlab {

// <source tree>/assets, the folder the build was configured from (compiled in, so a program
// finds it from any working directory).
std::string assets_dir();

// assets_dir() + "/" + relative, or InputError(where, "needs the asset ...") when that file is
// missing (a source tree whose assets/ was not checked out).
std::string asset_path(const std::string& relative, const std::string& where);

}  // namespace shadowlab
