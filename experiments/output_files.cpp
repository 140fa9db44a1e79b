#include "experiments/output_files.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"

namespace shadowlab {

void write_result_files(const std::string& dir, const std::string& prefix, const ShadowResult& r,
                        const std::string& technique, double camera_ms) {
  const std::string base = dir + "/" + prefix;
  write_exr_mask(base + "mask.exr", r.mask);
  write_png_grey(base + "mask.png", r.mask);
  if (!r.texels.empty()) write_exr_texels(base + "texel.exr", r.texels);
  nlohmann::json j;
  j["technique"] = technique;
  j["map_ms"] = r.map_ms;
  j["lookup_ms"] = r.lookup_ms;
  j["shadow_ms"] = r.shadow_ms();
  j["camera_ms"] = camera_ms;
  j["faces_needed"] = r.faces_needed;
  j["faces_rendered"] = r.faces_rendered;
  j["from_cache"] = r.from_cache;
  j["notes"] = r.notes;
  std::ofstream f(base + "timing.json");
  f << j.dump(2) << "\n";
  if (!f) throw InputError(base + "timing.json", "cannot write");
}

}  // namespace shadowlab
