// The .nsmw reader (techniques/nsm/nsm_weights.h): a file written by the test's own writer
// (nsm_weights_writer.h) reads back value for value, in f32 and f16; every corruption is an
// InputError naming the file and the reason, before any allocation larger than the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "core/error.h"
#include "nsm_weights_writer.h"
#include "techniques/nsm/nsm_weights.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

using test::NsmwDraft;

NsmArch tiny() {
  NsmArch a;
  EXPECT_TRUE(nsm_named_arch("tiny", a));
  return a;
}

std::string path_for(const std::string& name) {
  std::filesystem::create_directories(test::binary_path("nsmw"));
  return test::binary_path("nsmw/" + name + ".nsmw");
}

// The reason read_nsm_weights gives for `bytes` ("" when it reads them).
std::string refusal(const std::string& name, const std::vector<unsigned char>& bytes) {
  const std::string path = path_for(name);
  test::nsmw_save(path, bytes);
  try {
    read_nsm_weights(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, path);
    return e.reason;
  }
  return "";
}

std::string refusal_of(const std::string& name, const std::function<void(NsmwDraft&)>& edit) {
  NsmwDraft d = test::nsmw_draft(tiny(), 3);
  edit(d);
  return refusal(name, test::nsmw_bytes(d));
}

TEST(NsmWeights, NamedShapesHaveThePapersCounts) {
  // S Table 4 / spec §2: nsm3 39,248 and nsm5 653,648 weights without biases; 8,528 and 16,208
  // multiply-adds per pixel.
  NsmArch a;
  ASSERT_TRUE(nsm_named_arch("nsm5", a));
  uint64_t biases = 0;
  for (const NsmConv& c : nsm_conv_list(a)) biases += uint64_t(c.oc);
  EXPECT_EQ(nsm_parameter_count(a) - biases, 653648u);
  EXPECT_DOUBLE_EQ(nsm_macs_per_pixel(a), 16208.0);
  ASSERT_TRUE(nsm_named_arch("nsm3", a));
  biases = 0;
  for (const NsmConv& c : nsm_conv_list(a)) biases += uint64_t(c.oc);
  EXPECT_EQ(nsm_parameter_count(a) - biases, 39248u);
  EXPECT_DOUBLE_EQ(nsm_macs_per_pixel(a), 8528.0);
  EXPECT_FALSE(nsm_named_arch("nsm4", a));
}

TEST(NsmWeights, ReadsWhatTheWriterWroteInF32AndF16) {
  for (const bool f16 : {false, true}) {
    const NsmwDraft d = test::nsmw_draft(tiny(), 7, f16);
    const std::string path = path_for(f16 ? "good16" : "good32");
    test::nsmw_save(path, test::nsmw_bytes(d));
    const NsmWeights w = read_nsm_weights(path);
    EXPECT_EQ(w.arch.levels, 3);
    EXPECT_EQ(w.arch.widths, (std::vector<int>{4, 8}));
    EXPECT_EQ(w.arch.bottleneck, 16);
    EXPECT_EQ(w.features.size(), 4u);
    EXPECT_EQ(w.dtype, f16 ? "f16" : "f32");
    EXPECT_FLOAT_EQ(w.std[1], 0.75f);
    ASSERT_EQ(w.convs.size() * 2, d.tensors.size());
    for (size_t t = 0; t < d.tensors.size(); ++t) {
      const std::vector<float>& got = t % 2 ? w.convs[t / 2].bias : w.convs[t / 2].weight;
      ASSERT_EQ(got, d.tensors[t]) << t;
    }
    EXPECT_NE(w.provenance_json.find("test"), std::string::npos);
  }
}

TEST(NsmWeights, HalfDecodeIsExact) {
  EXPECT_EQ(nsm_half_to_float(0x3C00), 1.0f);
  EXPECT_EQ(nsm_half_to_float(0xC000), -2.0f);
  EXPECT_EQ(nsm_half_to_float(0x7BFF), 65504.0f);
  EXPECT_EQ(nsm_half_to_float(0x0400), std::ldexp(1.0f, -14));  // smallest normal
  EXPECT_EQ(nsm_half_to_float(0x0001), std::ldexp(1.0f, -24));  // smallest subnormal
  EXPECT_EQ(nsm_half_to_float(0x03FF), std::ldexp(1023.0f, -24));
  EXPECT_EQ(nsm_half_to_float(0x3555), 1365.0f / 4096.0f);       // 0.333251953125
  EXPECT_TRUE(std::signbit(nsm_half_to_float(0x8000)));
  EXPECT_TRUE(std::isinf(nsm_half_to_float(0x7C00)));
}

TEST(NsmWeights, RefusesBadFixedParts) {
  const std::vector<unsigned char> good = test::nsmw_bytes(test::nsmw_draft(tiny(), 3));
  auto edited = [&](const std::function<void(std::vector<unsigned char>&)>& f) {
    std::vector<unsigned char> b = good;
    f(b);
    return b;
  };
  EXPECT_NE(refusal("magic", edited([](auto& b) { b[0] = 'X'; test::nsmw_rehash(b); }))
                .find("magic"), std::string::npos);
  EXPECT_NE(refusal("version", edited([](auto& b) { b[4] = 2; test::nsmw_rehash(b); }))
                .find("version 2"), std::string::npos);
  EXPECT_NE(refusal("flip", edited([](auto& b) { b[b.size() / 2] ^= 1; })).find("checksum"),
            std::string::npos);
  EXPECT_NE(refusal("truncated", edited([](auto& b) { b.resize(b.size() - 64); }))
                .find("checksum"), std::string::npos);
  EXPECT_NE(refusal("short", {'N', 'S', 'M', 'W', 1, 0, 0}).find("shorter"), std::string::npos);
  EXPECT_NE(refusal("headerlen", edited([](auto& b) {
              b[10] = 0x7F;  // 8 MB of header in a file of a few KB
              test::nsmw_rehash(b);
            })).find("runs past the end"), std::string::npos);
  EXPECT_NE(refusal("badjson", edited([](auto& b) { b[12] = '['; test::nsmw_rehash(b); }))
                .find("JSON"), std::string::npos);
  // Not a regular file.
  const std::string dir = path_for("dir");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  try {
    read_nsm_weights(dir);
    ADD_FAILURE() << "a directory was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, dir);
    EXPECT_NE(e.reason.find("regular file"), std::string::npos) << e.reason;
  }
}

TEST(NsmWeights, RefusesHeadersThatDisagreeWithTheArchitecture) {
  struct Case {
    const char* name;
    std::function<void(NsmwDraft&)> edit;
    const char* reason;
  };
  const std::vector<Case> cases = {
      {"nolevels", [](NsmwDraft& d) { d.header.erase("levels"); }, "lacks \"levels\""},
      {"levels9", [](NsmwDraft& d) { d.header["levels"] = 9; }, "out of range"},
      {"levelsfloat", [](NsmwDraft& d) { d.header["levels"] = 3.5; }, "not an integer"},
      {"widths", [](NsmwDraft& d) { d.header["widths"] = {4, 8, 16}; }, "has 3 entries"},
      {"widthhuge", [](NsmwDraft& d) { d.header["widths"][1] = 1 << 20; }, "out of range"},
      {"meanlen", [](NsmwDraft& d) { d.header["mean"] = {0.0}; }, "has 1 entries"},
      {"std0", [](NsmwDraft& d) { d.header["std"][2] = 0.0; }, "not a positive float"},
      {"stdbig", [](NsmwDraft& d) { d.header["std"][2] = 1e300; }, "not a positive float"},
      {"dtype", [](NsmwDraft& d) { d.header["dtype"] = "f64"; }, "\"dtype\""},
      {"features", [](NsmwDraft& d) { d.header["features"] = nlohmann::json::array(); }, "features"},
      {"name", [](NsmwDraft& d) { d.header["tensors"][2]["name"] = "enc0.conv3.weight"; },
       "name is not \"enc0.conv1.weight\""},
      {"ntensors", [](NsmwDraft& d) { d.header["tensors"].erase(d.header["tensors"].size() - 1); },
       "\"tensors\" has"},
      // Widths that a tiny file cannot hold: refused by the offset check, before any allocation.
      {"hugeshape", [](NsmwDraft& d) {
         d.header["widths"] = {4096, 8};
         d.header["tensors"][0]["shape"] = {4096, 4, 3, 3};
       }, "run past the checksum"},
      {"nonfinite", [](NsmwDraft& d) { d.tensors[3][1] = INFINITY; }, "not finite"},
  };
  for (const Case& c : cases) {
    const std::string reason = refusal_of(c.name, c.edit);
    EXPECT_NE(reason.find(c.reason), std::string::npos) << c.name << ": '" << reason << "'";
  }
  EXPECT_NE(refusal_of("shape2", [](NsmwDraft& d) { d.header["tensors"][0]["shape"] = {4, 5, 3, 3}; })
                .find("shape is not [4,4,3,3]"), std::string::npos);
}

TEST(NsmWeights, RefusesBadOffsets) {
  auto with_offsets = [](const std::function<void(nlohmann::json&)>& edit, bool drop_last = false) {
    NsmwDraft d = test::nsmw_draft(tiny(), 3);
    if (drop_last) d.tensors.pop_back();  // the header still lists it
    // Lay out once to learn the offsets, then edit and keep them.
    std::vector<unsigned char> b = test::nsmw_bytes(d);
    const uint32_t len = uint32_t(b[8]) | uint32_t(b[9]) << 8 | uint32_t(b[10]) << 16;
    d.header = nlohmann::json::parse(std::string(b.begin() + 12, b.begin() + 12 + len));
    edit(d.header["tensors"]);
    return test::nsmw_bytes(d, true);
  };
  EXPECT_NE(refusal("misaligned", with_offsets([](nlohmann::json& t) {
              t[1]["offset"] = t[1]["offset"].get<int>() + 4;
            })).find("not 64-byte aligned"), std::string::npos);
  EXPECT_NE(refusal("overlap", with_offsets([](nlohmann::json& t) {
              t[1]["offset"] = t[0]["offset"];
            })).find("overlaps"), std::string::npos);
  EXPECT_NE(refusal("inheader", with_offsets([](nlohmann::json& t) { t[0]["offset"] = 0; }))
                .find("overlaps the header"), std::string::npos);
  EXPECT_NE(refusal("pastend", with_offsets([](nlohmann::json& t) {
              // head.conv1.weight is 16 floats: the bias would start where the checksum does.
              t[t.size() - 1]["offset"] = t[t.size() - 2]["offset"].get<int>() + 64;
            }, true)).find("run past the checksum"), std::string::npos);
  EXPECT_NE(refusal("negative", with_offsets([](nlohmann::json& t) { t[0]["offset"] = -64; }))
                .find("out of range"), std::string::npos);
}

}  // namespace
}  // namespace shadowlab
