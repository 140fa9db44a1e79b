#include "lab/output_files.h"

#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "core/output_file.h"
#include "lab/provenance.h"
#include "metric/flip.h"

namespace shadowlab {

void write_result_files(const std::string& dir, const std::string& prefix, const ShadowResult& r,
                        const std::string& technique, double camera_ms,
                        const nlohmann::json& provenance, const ImageF* shaded) {
  const std::string base = dir + "/" + prefix;
  ExrAttributes attributes = provenance_attributes(provenance);
  attributes.emplace_back("shadowlab:technique", technique);
  write_exr_mask(base + "mask.exr", r.mask, attributes);
  write_png_grey(base + "mask.png", r.mask);
  if (!r.texels.empty()) write_exr_texels(base + "texel.exr", r.texels, attributes);
  if (shaded) {
    write_exr_rgb(base + "shaded.exr", *shaded, attributes);
    write_png_rgb(base + "shaded.png", *shaded);
  }
  nlohmann::json j = timing_json(r);
  j["provenance"] = provenance;
  j["technique"] = technique;
  j["camera_ms"] = camera_ms;
  j["faces_needed"] = r.faces_needed;
  j["faces_rendered"] = r.faces_rendered;
  j["from_cache"] = r.from_cache;
  j["notes"] = r.notes;
  write_text_file(base + "timing.json", j.dump(2) + "\n");
}

void write_flip_map(const std::string& base, const ImageF& flip, const nlohmann::json& provenance) {
  ExrAttributes attributes = provenance_attributes(provenance);
  attributes.emplace_back("shadowlab:content", "LDR-FLIP error map of the shaded image");
  write_exr_mask(base + ".exr", flip, attributes);
  // write_png_grey encodes linear values as sRGB: give it the value whose encoding is the error.
  ImageF shown = flip;
  for (float& v : shown.data) v = float(srgb_to_linear(double(v)));
  write_png_grey(base + ".png", shown);
}

nlohmann::json timing_json(const ShadowResult& r) {
  nlohmann::json j;
  // A reference read from the cache was not timed: its times are null, not 0.
  auto ms = [&](double v) { return r.from_cache ? nlohmann::json(nullptr) : nlohmann::json(v); };
  j["faces_ms"] = ms(r.faces_ms);
  j["render_ms"] = ms(r.render_ms);
  j["filter_ms"] = ms(r.filter_ms);
  j["map_ms"] = ms(r.map_ms);
  j["lookup_ms"] = ms(r.lookup_ms);
  j["shadow_ms"] = ms(r.shadow_ms());
  // A network's phases (nsm: lookup_ms = features_ms + network_ms); absent elsewhere.
  if (r.network_ms > 0.0) {
    j["features_ms"] = ms(r.features_ms);
    j["network_ms"] = ms(r.network_ms);
  }
  // A ray tracer's phases (rts: lookup_ms = rays_ms + denoise_ms); absent elsewhere.
  if (r.rays_ms > 0.0) {
    j["rays_ms"] = ms(r.rays_ms);
    j["denoise_ms"] = ms(r.denoise_ms);
  }
  const WorkCounts& w = r.work;
  j["work"] = {{"triangles_submitted", w.triangles_submitted},
               {"triangles_binned", w.triangles_binned},
               {"texels_rendered", w.texels_rendered},
               {"texels_filtered", w.texels_filtered},
               {"pixels_looked_up", w.pixels_looked_up},
               {"taps", w.taps},
               {"taps_per_pixel", w.taps_per_pixel()},
               {"bytes_written", w.bytes_written},
               {"bytes_read", w.bytes_read},
               {"bytes_touched", w.bytes_touched()}};
  if (w.multiply_adds > 0) {
    j["work"]["multiply_adds"] = w.multiply_adds;
    j["work"]["activation_bytes"] = w.activation_bytes;
  }
  if (w.rays > 0) {
    j["work"]["rays"] = w.rays;
    j["work"]["filter_taps"] = w.filter_taps;
  }
  return j;
}

const char* work_csv_header() {
  return "faces_ms,render_ms,filter_ms,triangles_submitted,triangles_binned,texels_rendered,"
         "texels_filtered,pixels_looked_up,taps_per_pixel,bytes_written,bytes_read";
}

std::string work_csv_values(const ShadowResult& r) {
  const WorkCounts& w = r.work;
  // Not timed, no map: empty times and the zero counts a computed reference row writes, in the
  // same formats (taps per pixel with its four decimals).
  if (r.from_cache) return ",,,0,0,0,0,0,0.0000,0,0";
  return fmt::format("{:.4f},{:.4f},{:.4f},{},{},{},{},{},{:.4f},{},{}", r.faces_ms, r.render_ms,
                     r.filter_ms, w.triangles_submitted, w.triangles_binned, w.texels_rendered,
                     w.texels_filtered, w.pixels_looked_up, w.taps_per_pixel(), w.bytes_written,
                     w.bytes_read);
}

}  // namespace shadowlab
