#pragma once
// Writes a technique's result as files: mask.exr (float "Y"), mask.png (8-bit sRGB preview),
// texel.exr (UINT "texel", only when the technique has texels) and timing.json.
#include <string>

#include <nlohmann/json.hpp>

#include "techniques/registry/technique.h"

namespace shadowlab {

// Writes into dir with the given file-name prefix ("" → mask.exr, "csm_512_" → csm_512_mask.exr);
// with `shaded` also shaded.exr (linear RGB) and shaded.png (sRGB). `provenance`
// (lab/provenance.h) goes into timing.json and, as text attributes, every EXR header.
void write_result_files(const std::string& dir, const std::string& prefix, const ShadowResult& r,
                        const std::string& technique, double camera_ms,
                        const nlohmann::json& provenance, const ImageF* shaded = nullptr);

// A FLIP error map (metric/flip.h) as base + "flip.exr" (float "Y", the exact values) and
// base + "flip.png" (8-bit grey whose level is the error: 0 black, 1 white).
void write_flip_map(const std::string& base, const ImageF& flip, const nlohmann::json& provenance);

// The per-phase times and work counts of a result, as written in timing.json and sweep.json:
// {"faces_ms", "render_ms", "filter_ms", "map_ms", "lookup_ms", "shadow_ms", "work": {...}}.
nlohmann::json timing_json(const ShadowResult& r);
// CSV header fields and the values of the same columns (sweep.csv).
const char* work_csv_header();
std::string work_csv_values(const ShadowResult& r);

}  // namespace shadowlab
