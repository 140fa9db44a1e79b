// The generic "name:key=value,…" parser and strict number parsing (core/spec.h,
// core/parse_number.h), shared by technique specs and slides.
#include "core/spec.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace shadowlab
