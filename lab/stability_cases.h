#pragma once
// The stiff and extreme cases of docs/design.md §8 for the map-based techniques, each with its
// expected result stated as a bound. programs/stability prints every row; the test in
// tests/lab asserts every bound. Each row compares a technique's mask with Embree's
// hard-shadow mask evaluated at the same GBuffer points.
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "scenes/box_room.h"

namespace shadowlab {

struct StabilityRow {
  std::string case_name;     // e.g. "esm_exponent"
  std::string setting;       // what is varied in this row, e.g. "far=1e4"
  std::string spec;          // technique spec
  std::string expectation;   // the bound, in words
  size_t nonfinite = 0;      // NaN/Inf or out-of-[0,1] mask values (always expected 0)
  double mismatch = 0.0;     // share of covered pixels where (mask > 0.5) != (reference > 0.5)
  double lit_loss = 0.0;     // share of the reference's lit covered pixels with mask < 0.5 (acne)
  double shadow_leak = 0.0;  // mean mask over the reference's shadowed covered pixels (bleeding)
  double bound = 0.0;        // the limit `checked` is compared with
  double checked = 0.0;      // the value the bound applies to (one of the above)
  double leak_bound = 1.0;   // light-bleeding bound on shadow_leak (1 = none)
  bool pass = false;
};


// Runs every case (small images: the whole set takes a few seconds on 2 cores).
std::vector<StabilityRow> run_stability_cases();
// Table for stdout.
std::string stability_table(const std::vector<StabilityRow>& rows);

}  // namespace shadowlab
