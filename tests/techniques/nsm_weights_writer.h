#pragma once
// A small .nsmw writer for the tests (the file layout of techniques/nsm/nsm_weights.h, written
// here independently of the reader): the header is a JSON value the test may edit before the
// bytes are laid out, and the bytes may be edited after the checksum.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/hash.h"
#include "techniques/nsm/nsm_weights.h"

namespace shadowlab::test {

struct NsmwDraft {
  nlohmann::json header;
  std::vector<std::vector<float>> tensors;  // in the header's order
};

// A draft for `arch` with weights uniform in ±1/sqrt(fan-in) and small biases, mean/std per
// feature, dtype f32. Values are multiples of 1/1024 in f16 drafts (exact in binary16).
inline NsmwDraft nsmw_draft(const NsmArch& a, uint32_t seed, bool f16 = false) {
  std::mt19937 rng(seed);
  NsmwDraft d;
  nlohmann::json h;
  h["levels"] = a.levels;
  h["widths"] = a.widths;
  h["bottleneck"] = a.bottleneck;
  h["head"] = a.head;
  std::vector<std::string> names = {"z_over_zf", "z_minus_zf", "c_e_r", "d"};
  names.resize(size_t(a.features), "extra");
  h["features"] = names;
  std::vector<double> mean, sd;
  for (int i = 0; i < a.features; ++i) {
    mean.push_back(0.25 * i - 0.5);
    sd.push_back(0.5 + 0.25 * i);
  }
  h["mean"] = mean;
  h["std"] = sd;
  h["r_max"] = 0.3;
  h["scale_ref"] = 3.12;
  h["dtype"] = f16 ? "f16" : "f32";
  h["provenance"] = {{"writer", "test"}};
  nlohmann::json list = nlohmann::json::array();
  for (const NsmConv& c : nsm_conv_list(a)) {
    const float bound = 1.0f / std::sqrt(float(c.ic * c.k * c.k));
    std::uniform_real_distribution<float> u(-bound, bound);
    std::vector<float> w(size_t(c.oc) * c.ic * c.k * c.k), b(size_t(c.oc));
    for (float& v : w) v = u(rng);
    for (float& v : b) v = 0.1f * u(rng);
    if (f16) {
      for (float& v : w) v = std::round(v * 1024.0f) / 1024.0f;
      for (float& v : b) v = std::round(v * 1024.0f) / 1024.0f;
    }
    list.push_back({{"name", c.name + ".weight"}, {"shape", {c.oc, c.ic, c.k, c.k}}, {"offset", 0}});
    list.push_back({{"name", c.name + ".bias"}, {"shape", {c.oc}}, {"offset", 0}});
    d.tensors.push_back(std::move(w));
    d.tensors.push_back(std::move(b));
  }
  h["tensors"] = list;
  d.header = h;
  return d;
}

inline void nsmw_put32(std::vector<unsigned char>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back((unsigned char)(v >> (8 * i)));
}

// binary16 bits of v (v exact in binary16: the drafts' multiples of 1/1024 in range).
inline uint16_t nsmw_half_bits(float v) {
  if (v == 0.0f) return std::signbit(v) ? 0x8000 : 0;
  const uint16_t sign = v < 0 ? 0x8000 : 0;
  float m = std::fabs(v);
  int e = 0;
  const float fr = std::frexp(m, &e);  // m = fr · 2^e, fr in [0.5, 1)
  int exp16 = e - 1 + 15;
  if (exp16 <= 0) return uint16_t(sign | uint16_t(std::ldexp(m, 24)));  // subnormal
  const uint16_t man = uint16_t(std::ldexp(fr, 11)) & 1023u;
  return uint16_t(sign | uint16_t(exp16) << 10 | man);
}

// The file's bytes: offsets assigned in order (64-aligned) unless `keep_offsets`, then the
// checksum over every byte before it.
inline std::vector<unsigned char> nsmw_bytes(NsmwDraft d, bool keep_offsets = false) {
  const bool f16 = d.header["dtype"] == "f16";
  const size_t elem = f16 ? 2 : 4;
  // Offsets depend on the header's length, which depends on the offsets' digits: iterate.
  std::string text;
  for (int pass = 0; pass < 4; ++pass) {
    text = d.header.dump();
    size_t at = (12 + text.size() + 63) / 64 * 64;
    if (keep_offsets) break;
    for (size_t t = 0; t < d.tensors.size() && t < d.header["tensors"].size(); ++t) {
      d.header["tensors"][t]["offset"] = at;
      at = (at + d.tensors[t].size() * elem + 63) / 64 * 64;
    }
  }
  text = d.header.dump();
  std::vector<unsigned char> out = {'N', 'S', 'M', 'W'};
  nsmw_put32(out, 1);
  nsmw_put32(out, uint32_t(text.size()));
  out.insert(out.end(), text.begin(), text.end());
  for (size_t t = 0; t < d.tensors.size() && t < d.header["tensors"].size(); ++t) {
    const long long offset = d.header["tensors"][t]["offset"].get<long long>();
    if (offset > 0 && out.size() < size_t(offset)) out.resize(size_t(offset), 0);
    for (float v : d.tensors[t]) {
      if (f16) {
        const uint16_t b = nsmw_half_bits(v);
        out.push_back((unsigned char)(b & 255));
        out.push_back((unsigned char)(b >> 8));
      } else {
        uint32_t b;
        std::memcpy(&b, &v, 4);
        nsmw_put32(out, b);
      }
    }
  }
  out.resize((out.size() + 63) / 64 * 64, 0);
  Fnv1a h;
  h.bytes(out.data(), out.size());
  for (int i = 0; i < 8; ++i) out.push_back((unsigned char)(h.h >> (8 * i)));
  return out;
}

// Recomputes the last 8 bytes (after an edit that should reach a later check).
inline void nsmw_rehash(std::vector<unsigned char>& b) {
  Fnv1a h;
  h.bytes(b.data(), b.size() - 8);
  for (int i = 0; i < 8; ++i) b[b.size() - 8 + size_t(i)] = (unsigned char)(h.h >> (8 * i));
}

inline void nsmw_save(const std::string& path, const std::vector<unsigned char>& b) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

}  // namespace shadowlab::test
