#include "techniques/nsm/nsm_weights.h"

#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/hash.h"
#include "core/json_check.h"

namespace shadowlab {

namespace {

constexpr size_t kNsmwFixedHead = 12;  // magic, version, header length
constexpr size_t kNsmwChecksum = 8;

uint32_t nsmw_le32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
uint64_t nsmw_le64(const unsigned char* p) { return uint64_t(nsmw_le32(p)) | uint64_t(nsmw_le32(p + 4)) << 32; }

// Checked reads of the header's fields: each failure names the field.
struct NsmwHeader {
  const nlohmann::json& j;
  const std::string& path;

  [[noreturn]] void fail(const std::string& reason) const { throw InputError(path, reason); }
  const nlohmann::json& field(const char* key) const {
    auto it = j.find(key);
    if (it == j.end()) fail(std::string("header lacks \"") + key + "\"");
    return *it;
  }
  long long integer(const nlohmann::json& v, const std::string& what, long long lo,
                    long long hi) const {
    if (!v.is_number_integer()) fail(what + " is not an integer");
    if (v.is_number_unsigned() && v.get<unsigned long long>() > (unsigned long long)hi)
      fail(what + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    const long long x = v.get<long long>();
    if (x < lo || x > hi)
      fail(what + " is " + std::to_string(x) + ", out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    return x;
  }
  int int_field(const char* key, int lo, int hi) const {
    return int(integer(field(key), std::string("\"") + key + "\"", lo, hi));
  }
  double number(const nlohmann::json& v, const std::string& what) const {
    if (!v.is_number()) fail(what + " is not a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(what + " is not finite");
    return x;
  }
  const nlohmann::json& array(const char* key, size_t n) const {
    const nlohmann::json& v = field(key);
    if (!v.is_array()) fail(std::string("\"") + key + "\" is not an array");
    if (v.size() != n)
      fail(std::string("\"") + key + "\" has " + std::to_string(v.size()) + " entries, expected " +
           std::to_string(n));
    return v;
  }
};

bool nsmw_finite(float v) { return std::isfinite(v); }

}  // namespace

float nsm_half_to_float(uint16_t h) {
  const uint32_t sign = uint32_t(h >> 15) << 31;
  const int exp = (h >> 10) & 31;
  const uint32_t man = h & 1023u;
  float mag;
  if (exp == 0)
    mag = std::ldexp(float(man), -24);  // subnormal (or zero): man · 2^−24, exact
  else if (exp == 31)
    mag = man ? std::nanf("") : INFINITY;
  else
    mag = std::ldexp(float(1024u + man), exp - 25);
  uint32_t bits;
  std::memcpy(&bits, &mag, 4);
  bits |= sign;
  float out;
  std::memcpy(&out, &bits, 4);
  return out;
}

bool nsm_named_arch(const std::string& name, NsmArch& arch) {
  arch = NsmArch{};
  if (name == "nsm3") arch = {3, {16, 32}, 64, 16, 4};
  else if (name == "nsm5") arch = {5, {16, 32, 64, 128}, 256, 16, 4};
  else if (name == "nsm7e") arch = {7, {16, 32, 64, 96, 128, 192}, 256, 16, 4};
  else if (name == "tiny") arch = {3, {4, 8}, 16, 16, 4};
  else return false;
  return true;
}

std::vector<NsmConv> nsm_conv_list(const NsmArch& a) {
  std::vector<NsmConv> out;
  auto add = [&](std::string name, int oc, int ic, int k) {
    NsmConv c;
    c.name = std::move(name);
    c.oc = oc;
    c.ic = ic;
    c.k = k;
    out.push_back(std::move(c));
  };
  const int L = a.levels;
  for (int l = 0; l <= L - 2; ++l) {
    const int in = l == 0 ? a.features : a.widths[size_t(l) - 1];
    add("enc" + std::to_string(l) + ".conv3", a.widths[size_t(l)], in, 3);
    add("enc" + std::to_string(l) + ".conv1", a.widths[size_t(l)], a.widths[size_t(l)], 1);
  }
  const int inner = a.widths[size_t(L) - 2];
  add("mid.conv3", a.bottleneck, inner, 3);
  add("mid.conv1", inner, a.bottleneck, 1);
  for (int l = L - 2; l >= 1; --l) {
    add("dec" + std::to_string(l) + ".conv3", a.widths[size_t(l)], a.widths[size_t(l)], 3);
    add("dec" + std::to_string(l) + ".conv1", a.widths[size_t(l) - 1], a.widths[size_t(l)], 1);
  }
  add("dec0.conv3", a.widths[0], a.widths[0], 3);
  add("dec0.conv1", a.head, a.widths[0], 1);
  add("head.conv1", 1, a.head, 1);
  return out;
}

double nsm_macs_per_pixel(const NsmArch& a) {
  // Level l runs at 1/4^l of the pixels: the encoder and decoder convs of level l (and the
  // bottleneck at level L−1); the head at level 0.
  double macs = 0;
  for (const NsmConv& c : nsm_conv_list(a)) {
    int level = 0;
    if (c.name.rfind("mid.", 0) == 0) level = a.levels - 1;
    else if (c.name.rfind("enc", 0) == 0 || c.name.rfind("dec", 0) == 0) level = c.name[3] - '0';
    macs += double(c.oc) * c.ic * c.k * c.k / std::ldexp(1.0, 2 * level);
  }
  return macs;
}

uint64_t nsm_parameter_count(const NsmArch& a) {
  uint64_t n = 0;
  for (const NsmConv& c : nsm_conv_list(a)) n += uint64_t(c.oc) * c.ic * c.k * c.k + c.oc;
  return n;
}

NsmWeights read_nsm_weights(const std::string& path) {
  const std::vector<unsigned char> bytes = read_input_bytes(path, kNsmWeightsFileLimit);
  auto fail = [&](const std::string& reason) -> void { throw InputError(path, reason); };
  const size_t size = bytes.size();
  if (size < kNsmwFixedHead + kNsmwChecksum)
    fail("is " + std::to_string(size) + " bytes, shorter than a weights file's fixed parts (20)");
  if (std::memcmp(bytes.data(), "NSMW", 4) != 0) fail("not a weights file (magic is not NSMW)");
  const uint32_t version = nsmw_le32(bytes.data() + 4);
  if (version != 1) fail("version " + std::to_string(version) + " (this reader reads version 1)");
  Fnv1a hash;
  hash.bytes(bytes.data(), size - kNsmwChecksum);
  if (hash.h != nsmw_le64(bytes.data() + size - kNsmwChecksum))
    fail("checksum mismatch (the file is corrupt or truncated)");
  const uint32_t header_len = nsmw_le32(bytes.data() + 8);
  if (header_len > size - kNsmwFixedHead - kNsmwChecksum)
    fail("header length " + std::to_string(header_len) + " runs past the end of the file");
  const char* text = reinterpret_cast<const char*>(bytes.data() + kNsmwFixedHead);
  check_json_text(text, header_len, path);
  const nlohmann::json j = nlohmann::json::parse(text, text + header_len);
  if (!j.is_object()) fail("the header is not a JSON object");
  const NsmwHeader h{j, path};

  NsmWeights w;
  NsmArch& a = w.arch;
  a.levels = h.int_field("levels", 2, 8);
  const nlohmann::json& widths = h.array("widths", size_t(a.levels) - 1);
  for (size_t i = 0; i < widths.size(); ++i)
    a.widths.push_back(int(h.integer(widths[i], "\"widths\"[" + std::to_string(i) + "]", 1, 4096)));
  a.bottleneck = h.int_field("bottleneck", 1, 4096);
  a.head = h.int_field("head", 1, 4096);
  const nlohmann::json& features = h.field("features");
  if (!features.is_array() || features.empty() || features.size() > 64)
    fail("\"features\" is not an array of 1 to 64 names");
  for (const auto& f : features) {
    if (!f.is_string()) fail("\"features\" holds a value that is not a string");
    w.features.push_back(f.get<std::string>());
  }
  a.features = int(w.features.size());
  const nlohmann::json& mean = h.array("mean", w.features.size());
  const nlohmann::json& sd = h.array("std", w.features.size());
  for (size_t i = 0; i < w.features.size(); ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    const float m = float(h.number(mean[i], "\"mean\"" + idx));
    const float s = float(h.number(sd[i], "\"std\"" + idx));
    if (!std::isfinite(m)) fail("\"mean\"" + idx + " overflows a float");
    if (!(s > 0) || !std::isfinite(s)) fail("\"std\"" + idx + " is not a positive float");
    w.mean.push_back(m);
    w.std.push_back(s);
  }
  w.r_max = h.number(h.field("r_max"), "\"r_max\"");
  w.scale_ref = h.number(h.field("scale_ref"), "\"scale_ref\"");
  const nlohmann::json& dtype = h.field("dtype");
  if (!dtype.is_string() || (dtype != "f32" && dtype != "f16"))
    fail("\"dtype\" is not \"f32\" or \"f16\"");
  w.dtype = dtype.get<std::string>();
  const size_t elem = w.dtype == "f16" ? 2 : 4;
  auto prov = j.find("provenance");
  w.provenance_json = prov == j.end() ? "{}" : prov->dump();

  w.convs = nsm_conv_list(a);
  const nlohmann::json& tensors = h.array("tensors", 2 * w.convs.size());
  const size_t data_begin = kNsmwFixedHead + header_len;
  const size_t data_end = size - kNsmwChecksum;
  size_t previous_end = data_begin;
  for (size_t t = 0; t < tensors.size(); ++t) {
    NsmConv& c = w.convs[t / 2];
    const bool is_weight = t % 2 == 0;
    const std::string name = c.name + (is_weight ? ".weight" : ".bias");
    const nlohmann::json& e = tensors[t];
    const std::string where = "tensor " + std::to_string(t) + " (" + name + ")";
    if (!e.is_object()) fail(where + " is not a JSON object");
    const auto n = e.find("name");
    if (n == e.end() || !n->is_string() || *n != name)
      fail(where + ": name is not \"" + name + "\" (tensors follow the network order)");
    std::vector<long long> want = {c.oc};
    if (is_weight) want = {c.oc, c.ic, c.k, c.k};
    const auto s = e.find("shape");
    bool shape_ok = s != e.end() && s->is_array() && s->size() == want.size();
    for (size_t i = 0; shape_ok && i < want.size(); ++i)
      shape_ok = (*s)[i].is_number_integer() && (*s)[i].get<long long>() == want[i];
    if (!shape_ok) {
      std::string ws = "[";
      for (size_t i = 0; i < want.size(); ++i) ws += (i ? "," : "") + std::to_string(want[i]);
      fail(where + ": shape is not " + ws + "] (the architecture's)");
    }
    const auto o = e.find("offset");
    if (o == e.end()) fail(where + " lacks \"offset\"");
    const long long offset = h.integer(*o, where + ": offset", 0, (long long)size);
    if (offset % 64 != 0) fail(where + ": offset " + std::to_string(offset) + " is not 64-byte aligned");
    if (size_t(offset) < previous_end)
      fail(where + ": offset " + std::to_string(offset) +
           " overlaps the header or the previous tensor");
    size_t count = 1;
    for (long long d : want) count *= size_t(d);  // ≤ 4096² · 9: no overflow
    const size_t nbytes = count * elem;
    if (nbytes > data_end - size_t(offset))
      fail(where + ": " + std::to_string(nbytes) + " bytes at offset " + std::to_string(offset) +
           " run past the checksum at " + std::to_string(data_end));
    previous_end = size_t(offset) + nbytes;
    std::vector<float>& dst = is_weight ? c.weight : c.bias;
    dst.resize(count);  // bounded by the file's size (checked above)
    const unsigned char* src = bytes.data() + offset;
    for (size_t i = 0; i < count; ++i) {
      float v;
      if (elem == 2) v = nsm_half_to_float(uint16_t(src[2 * i] | src[2 * i + 1] << 8));
      else {
        const uint32_t b = nsmw_le32(src + 4 * i);
        std::memcpy(&v, &b, 4);
      }
      if (!nsmw_finite(v)) fail(where + ": value " + std::to_string(i) + " is not finite");
      dst[i] = v;
    }
  }
  return w;
}

}  // namespace shadowlab
