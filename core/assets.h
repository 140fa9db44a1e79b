#pragma once
// Where the shared read-only model assets live (bunny, palm tree, plants). Built-in scenes that
// use real models (make_builtin_scene("bunny")) read them from here.
#include <string>

namespace shadowlab {

// The assets folder: $SHADOWLAB_ASSETS if set; else <source tree>/../shared/assets (the
// team's layout, compiled in); else /work/shared/assets (where our machines keep it, so a
// clone elsewhere — CI's — still finds it); "" when none exists.
std::string shared_assets_dir();

// shared_assets_dir() + "/" + relative, or InputError(where, "needs the shared asset ...") when
// the folder or the file is missing.
std::string shared_asset_path(const std::string& relative, const std::string& where);

}  // namespace shadowlab
