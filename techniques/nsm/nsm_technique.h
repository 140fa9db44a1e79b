#pragma once
// Neural Shadow Mapping as a technique (docs/techniques/nsm.md): one plain base map, the
// network's input features over the GBuffer, and the network's forward pass. Its phases:
//   faces    the base map's faces some covered pixel reads        (faces_ms)
//   render   the base map (csm, fp32, nearest texel, no bias)     (render_ms; map_ms = both)
//   features the network's input planes                           (features_ms)
//   network  the UNet's forward pass                              (network_ms)
// lookup_ms = features_ms + network_ms, so shadow_ms compares with every other technique's.
#include <cstdint>
#include <string>
#include <vector>

#include "techniques/nsm/nsm_features.h"
#include "techniques/nsm/nsm_network.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/registry/technique.h"
#include "techniques/registry/technique_keys.h"

namespace shadowlab {

// Defaults, ranges and meanings: the declarations of nsm_keys().
struct NsmParams {
  std::string weights;  // "default" or a .nsmw file
  int res{};            // base map resolution per face
  FaceLayoutKind layout = FaceLayoutKind::Cube;  // the base map's layout
  NsmPrecision precision = NsmPrecision::f32;
};
const std::vector<KeyDecl<NsmParams>>& nsm_keys();
NsmParams parse_nsm(const TechniqueSpec& spec, const char* flag);

// The file `weights` names: the shipped model (assets/nsm/default.nsmw) for "default".
std::string nsm_weights_path(const std::string& weights, const char* flag);
// Reads and checks the weights a spec names (InputError naming the file), including that every
// input it declares is a feature this build computes (techniques/nsm/nsm_features.h).
NsmWeights load_nsm_weights(const NsmParams& p, const char* flag);

ShadowResult run_nsm(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                     const RunOptions& options);
// The network's input planes for `g`, as run_nsm computes them: the spec's base map rendered
// (its needed faces), then the features its weights declare, or every candidate feature
// (nsm_feature_names) with `every_candidate`.
NsmFeatures nsm_spec_features(const TechniqueSpec& spec, const Scene& scene, const GBuffer& g,
                              bool every_candidate, const char* flag);
// The base map's faces and the network's stored activations at the GBuffer's size.
uint64_t nsm_technique_bytes(const TechniqueSpec& spec, const Scene& scene, const GBuffer* g,
                             const char* flag);

}  // namespace shadowlab
