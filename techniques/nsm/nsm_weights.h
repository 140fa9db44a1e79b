#pragma once
// The weights of the Neural Shadow Mapping network (docs/techniques/nsm.md, "Network and
// inference"): the .nsmw file's reader and the architecture it must describe.
//
// File layout, little-endian: magic "NSMW", u32 version 1, u32 header length N, N bytes of JSON
// header, zero padding to a multiple of 64, the tensors (each 64-byte aligned at the offset the
// header gives), then the FNV-1a 64 (core/hash.h) of every byte before those last 8.
// The header: {"levels":L,"widths":[C0..C(L-2)],"bottleneck":B,"head":16,"features":[names],
// "mean":[...],"std":[...],"r_max":0.3,"scale_ref":3.12,"dtype":"f32"|"f16",
// "tensors":[{"name":..,"shape":[..],"offset":..},...],"provenance":{...}}. The tensors are
// exactly nsm_tensor_list(arch) in that order; f16 tensors are decoded to fp32 at load (exact).
#include <cstdint>
#include <string>
#include <vector>

#include "core/input_file.h"

namespace shadowlab {

// A weights file is a few MB (nsm7e in fp32: 6.5 MB); 256 MiB leaves a wide margin and bounds
// what a corrupt header can make the reader allocate.
constexpr InputLimit kNsmWeightsFileLimit{uint64_t(256) << 20, "a network weights file"};

// The UNet's shape: L levels, widths C_0..C_{L-2}, bottleneck B, head width, F inputs.
struct NsmArch {
  int levels = 0;
  std::vector<int> widths;  // L − 1 entries
  int bottleneck = 0;
  int head = 16;
  int features = 4;
};

// Named shapes: "nsm3", "nsm5", "nsm7e", "tiny" (4 features). False for another name.
bool nsm_named_arch(const std::string& name, NsmArch& arch);

// One convolution: weight [oc][ic][k][k] (k = 1 or 3), bias [oc].
struct NsmConv {
  std::string name;  // "enc0.conv3", ..., "head.conv1"
  int oc = 0, ic = 0, k = 0;
  std::vector<float> weight, bias;
};

// The convolutions of an architecture in network order, with their shapes and empty data:
// enc{l}.conv3, enc{l}.conv1 (l = 0..L−2), mid.conv3, mid.conv1, dec{l}.conv3, dec{l}.conv1
// (l = L−2..0), head.conv1.
std::vector<NsmConv> nsm_conv_list(const NsmArch& arch);
// Multiply-adds per input pixel (biases not counted) and the parameter count (with biases).
double nsm_macs_per_pixel(const NsmArch& arch);
uint64_t nsm_parameter_count(const NsmArch& arch);

struct NsmWeights {
  NsmArch arch;
  std::vector<std::string> features;
  std::vector<float> mean, std;  // per feature, fp32 as the network uses them
  double r_max = 0.3, scale_ref = 3.12;
  std::string dtype;             // "f32" or "f16" (as stored)
  std::string provenance_json;   // the header's "provenance", re-serialized ("{}" when absent)
  std::vector<NsmConv> convs;    // nsm_conv_list(arch) with data
};

// Reads and checks a .nsmw file. Throws InputError(path, reason) for: not a regular file or over
// kNsmWeightsFileLimit; shorter than its fixed parts; a wrong magic, version or checksum; a
// header that is not checked JSON (core/json_check.h) or lacks or mistypes a field; an
// architecture out of range (levels 2..8, widths and bottleneck 1..4096, head 1..4096,
// features 1..64); mean/std of another length, not finite, or std not > 0; a tensor list other
// than the architecture's (name, order, shape); an offset not 64-aligned, inside the header,
// overlapping the previous tensor or past the checksum; a weight that is not finite.
NsmWeights read_nsm_weights(const std::string& path);

// IEEE binary16 bits to float (exact; used by the reader, exposed for tests).
float nsm_half_to_float(uint16_t h);

}  // namespace shadowlab
