#pragma once
// Stored shadow-map depth precision (the spec key `depth=`, on csm and the face-map family).
// Maps store normalised radial distance d = |p − L| / far in [0, 1] (+inf where empty). A
// quantized map rounds each stored d to the nearest code of its format and stores the decoded
// value; lookups compare the receiver's exact (float) biased distance with it, as a modern
// depth-compare against a low-precision map does.
//   f32      float32 as rendered (no quantization; the default)
//   16       16-bit linear: d = k / 65535
//   8        8-bit linear:  d = k / 255   (the step is far/255: 7.8 cm for a 20 m range)
//   8cubic   8-bit cubic ramp (Everitt's alpha ramp, Dowling §4): d = (k / 255)³, i.e. the
//            code is round(255·∛d): steps are 3·d^(2/3)/255 wide, finer near the light
//            (d = 0.01: 5.5e-4, 14× finer than linear) and coarser far away (d = 1: 3× coarser)
// Values above 1 clamp to code max; +inf (nothing seen) stays +inf.
#include <cstddef>
#include <string>
#include <vector>

namespace shadowlab {

enum class DepthFormat { F32, U16, U8, U8Cubic };

// The key's accepted texts, in the order of the enum.
const std::vector<std::string>& depth_format_names();
DepthFormat depth_format_from_name(const std::string& name);  // name must be one of them

// Decoded value of the code nearest to d in format `f`.
float quantize_depth(float d, DepthFormat f);
// Quantizes n stored values in place (no-op for F32).
void quantize_depths(float* d, size_t n, DepthFormat f);

}  // namespace shadowlab
