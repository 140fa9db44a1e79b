#pragma once
// Parameter spaces of the tuner (lab/tuner.h): one technique and a domain per key,
//   "csm:res=256..2048/x2,pcf=1|3|5,bias=0.001..0.05/log6"
// Domains:
//   V              one value;
//   V1|V2|…        a list (no repeats);
//   A..B/S         A, A+S, …, B (S > 0; B − A must be a whole number of steps);
//   A..B           the same with S = 1, for integer A and B;
//   A..B/xF        A, A·F, A·F², …, B (F > 1, A > 0; B/A a whole power of F);
//   A..B/linN      N evenly spaced values from A to B (N >= 2);
//   A..B/logN      N log-spaced values from A to B (N >= 2, A > 0).
// Computed values are written with 4 significant digits (whole numbers exactly); the text is
// what runs, so every table shows the value that was measured. Errors (unknown syntax, an empty
// range A > B, a step that never reaches B, repeated values, more than kMaxDomainValues
// values) are InputErrors naming the flag and the space.
#include <cstddef>
#include <string>
#include <vector>

namespace shadowlab {

constexpr size_t kMaxDomainValues = 4096;

struct ParamDomain {
  std::string key;
  std::vector<std::string> values;  // value texts, in domain order
};

struct ParamSpace {
  std::string text;                 // the space as given
  std::string technique;            // the name before ':'
  std::vector<ParamDomain> keys;    // in the order given
  size_t size() const;              // number of points (product of the domains' sizes)
};

ParamSpace parse_param_space(const std::string& text, const std::string& flag);

// True when a and b describe the same points: one technique, the same keys, and each key's values
// the same set as parsed (core/spec.h same_spec_value: "pcf=3|1" and "pcf=01|3" are one domain).
bool same_space(const ParamSpace& a, const ParamSpace& b);

// The point with odometer index i (last key fastest) as spec text "name:k=v,…" (keys in the
// space's order; parse_technique_spec makes it canonical).
std::string space_point(const ParamSpace& space, size_t i);

// tune's spaces without --space: per technique of a fixed list, its keys that declare
// a tune domain (techniques/registry/technique_keys.h, technique_tune_space).
std::vector<std::string> default_param_spaces();

// The values of one domain text (the part after '=').
std::vector<std::string> parse_domain(const std::string& text, const std::string& flag);

}  // namespace shadowlab
