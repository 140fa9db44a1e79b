#pragma once
// Technique specifications: core/spec.h's generic "name:key=value,…" with the technique
// registry's name (techniques/registry/technique.h).
#include "core/spec.h"

namespace shadowlab {

using TechniqueSpec = Spec;

inline TechniqueSpec parse_technique_spec(const std::string& text, const std::string& flag) {
  return parse_spec(text, flag);
}

}  // namespace shadowlab
