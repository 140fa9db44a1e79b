#pragma once
// Writes a technique's result as files: mask.exr (float "Y"), mask.png (8-bit sRGB preview),
// texel.exr (UINT "texel", only when the technique has texels) and timing.json.
#include <string>

#include "techniques/technique.h"

namespace shadowlab {

// Writes into dir with the given file-name prefix ("" → mask.exr, "csm_512_" → csm_512_mask.exr).
void write_result_files(const std::string& dir, const std::string& prefix, const ShadowResult& r,
                        const std::string& technique, double camera_ms);

}  // namespace shadowlab
