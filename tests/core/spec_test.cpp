// The generic "name:key=value,…" parser and strict number parsing (core/spec.h,
// core/parse_number.h), shared by technique specs and slides.
#include "core/spec.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_paths.h"

#include "core/error.h"
#include "core/parse_number.h"
#include "core/slide.h"

namespace shadowlab {
namespace {

TEST(ParseNumber, DecimalOnly) {
  double d = 0.0;
  long l = 0;
  for (const char* ok : {"64", "-3", "0.25", "1e-3", "2.5E+2", ".5", "5."}) EXPECT_TRUE(parse_double(ok, d)) << ok;
  EXPECT_TRUE(parse_double("1e-3", d) && d == 0.001);
  for (const char* bad : {"+64", " 64", "64 ", "0x1p-3", "0x10", "inf", "nan", "", "-", "1e", "1e+",
                          "1,5", "--1", "1e999"})
    EXPECT_FALSE(parse_double(bad, d)) << bad;
  EXPECT_TRUE(parse_long("-17", l) && l == -17);
  for (const char* bad : {"+64", " 64", "64 ", "0x10", "1.0", "", "99999999999999999999"})
    EXPECT_FALSE(parse_long(bad, l)) << bad;
}

TEST(ParseNumber, RangesPrintReadably) {
  EXPECT_EQ(number_text(0.0), "0");
  EXPECT_EQ(number_text(10000.0), "10000");
  EXPECT_EQ(number_text(0.99), "0.99");
  EXPECT_EQ(number_text(1e-6), "1e-06");
  try {
    const Spec s = parse_spec("csm:bias=2000", "--technique");
    SpecReader r(s, "--technique");
    r.get_double("bias", 0.01, 0.0, 1e3);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("outside [0, 1000]"), std::string::npos) << e.what();
  }
}

TEST(Spec, StrictItems) {
  for (const char* bad : {"csm:res=64,", "csm:,res=64", "csm:res=64,,pcf=3", "csm:res=", "csm:=3",
                          "csm:res=64,res=128", ":res=1", "csm:"})
    EXPECT_THROW(parse_spec(bad, "--technique"), InputError) << bad;
  const Spec s = parse_spec("csm:res=64,pcf=3", "--technique");
  EXPECT_EQ(s.text, "csm:pcf=3,res=64");
  // Lists keep empty items for parse_spec to reject.
  EXPECT_EQ(split_spec_list("csm:res=64,pcf=3,rt"), (std::vector<std::string>{"csm:res=64,pcf=3", "rt"}));
  EXPECT_EQ(split_spec_list("csm,,rt"), (std::vector<std::string>{"csm", "", "rt"}));
  EXPECT_EQ(split_spec_list(""), (std::vector<std::string>{""}));
}

// Slides go through the same parser: a repeated key, a trailing comma and a spelled-out sign
// are errors (the last value used to win silently).
TEST(Spec, SlideSpecsAreStrict) {
  for (const char* bad : {"grid:amp=1,amp=0.5,freq=2", "grid:amp=1,freq=2,", "grid:amp=+1,freq=2",
                          "grid:amp=1", "spot:amp=1", "spot:res=0x20", "grid:amp= 1,freq=2"})
    EXPECT_THROW(make_slide(bad, "--slide"), InputError) << bad;
  EXPECT_NO_THROW(make_slide("grid:amp=1,freq=2,res=64", "--slide"));
}

// A PNG header claiming w × h RGB pixels (signature, IHDR with its CRC, IEND): enough for the
// size check, which must refuse it before any decoding.
std::string png_header(uint32_t w, uint32_t h) {
  auto crc32 = [](const std::string& bytes) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto be32 = [](uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const std::string ihdr = "IHDR" + be32(w) + be32(h) + std::string{8, 2, 0, 0, 0};
  const std::string iend = "IEND";
  return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + ihdr + be32(crc32(ihdr)) + be32(0) + iend +
         be32(crc32(iend));
}

// A slide image larger than 4096² texels is refused from its header (an 8192² PNG of 261 KB
// used to be decoded to a 1.84 GB peak).
TEST(Spec, OversizedSlideImagesAreRefusedBeforeDecoding) {
  const std::string path = test::binary_path("slide_8192.png");
  std::ofstream(path, std::ios::binary) << png_header(8192, 8192);
  try {
    make_slide(path, "--slide");
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("8192x8192"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("limit"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadowlab
