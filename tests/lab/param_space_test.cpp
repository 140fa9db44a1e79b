// Parameter spaces of the tuner: every domain form against values worked out by hand, and the
// malformed spaces refused with the reason.
#include <gtest/gtest.h>

#include <cstdint>

#include "core/error.h"
#include "lab/param_space.h"

namespace shadowlab {
namespace {

using V = std::vector<std::string>;

TEST(ParamSpace, EveryDomainFormGivesItsValues) {
  EXPECT_EQ(parse_domain("3", "f"), (V{"3"}));
  EXPECT_EQ(parse_domain("1|3|5", "f"), (V{"1", "3", "5"}));
  EXPECT_EQ(parse_domain("2..5", "f"), (V{"2", "3", "4", "5"}));
  EXPECT_EQ(parse_domain("256..2048/x2", "f"), (V{"256", "512", "1024", "2048"}));
  EXPECT_EQ(parse_domain("1..2/0.25", "f"), (V{"1", "1.25", "1.5", "1.75", "2"}));
  // Decimal steps are not exact in binary: 0.1 × 3 must still land on 0.3.
  EXPECT_EQ(parse_domain("0..0.3/0.1", "f"), (V{"0", "0.1", "0.2", "0.3"}));
  EXPECT_EQ(parse_domain("0..1/lin5", "f"), (V{"0", "0.25", "0.5", "0.75", "1"}));
  // 0.001 · 50^(i/5): 0.001, 0.002187, 0.004782, 0.01046, 0.02287, 0.05 (4 significant digits).
  EXPECT_EQ(parse_domain("0.001..0.05/log6", "f"),
            (V{"0.001", "0.002187", "0.004782", "0.01046", "0.02287", "0.05"}));
  EXPECT_EQ(parse_domain("10..1000/log3", "f"), (V{"10", "100", "1000"}));
  EXPECT_EQ(parse_domain("5..5/1", "f"), (V{"5"}));
}

// docs/programs/tune.md: whole numbers below 1e15 exactly, others to 4 significant digits, an
// exponent without '+' (the text a spec accepts). 1e18 and 1e16 are whole but beyond 1e15: "1e18";
// 1/3 steps give 4 digits; 123456.5 and 123457.5 both read 1.235e5, so they are refused as one
// value given twice rather than run as two.
TEST(ParamSpace, ComputedValuesHaveFourSignificantDigits) {
  EXPECT_EQ(parse_domain("0..1e18/lin2", "f"), (V{"0", "1e18"}));
  EXPECT_EQ(parse_domain("1e16..1e18/x10", "f"), (V{"1e16", "1e17", "1e18"}));
  EXPECT_EQ(parse_domain("1..2/lin4", "f"), (V{"1", "1.333", "1.667", "2"}));
  EXPECT_EQ(parse_domain("123456.5|2", "f"), (V{"123456.5", "2"}));  // given values stay as given
  EXPECT_THROW(parse_domain("123456.5..123457.5/lin2", "f"), InputError);
  // A one-digit exponent is written with one digit: 12345.5 → "1.235e4", not "1.235e04".
  EXPECT_EQ(parse_domain("1..24690/lin3", "f"), (V{"1", "1.235e4", "24690"}));
}

TEST(ParamSpace, PointsAreTheOdometerOfTheDomains) {
  const ParamSpace s = parse_param_space("csm:res=256..1024/x2,pcf=1|3", "--space");
  EXPECT_EQ(s.technique, "csm");
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(space_point(s, 0), "csm:res=256,pcf=1");
  EXPECT_EQ(space_point(s, 1), "csm:res=256,pcf=3");
  EXPECT_EQ(space_point(s, 2), "csm:res=512,pcf=1");
  EXPECT_EQ(space_point(s, 5), "csm:res=1024,pcf=3");
  const ParamSpace bare = parse_param_space("tsm", "--space");
  EXPECT_EQ(bare.size(), 1u);
  EXPECT_EQ(space_point(bare, 0), "tsm");
}

TEST(ParamSpace, MalformedDomainsAreRefusedWithTheReason) {
  auto reason = [](const std::string& space) {
    try {
      parse_param_space(space, "--space");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(reason("csm:res=2048..256/x2").find("empty range"), std::string::npos);
  EXPECT_NE(reason("csm:res=256..2000/x2").find("never reach 2000"), std::string::npos);
  EXPECT_NE(reason("csm:bias=0..1/0.3").find("never reach 1"), std::string::npos);
  EXPECT_NE(reason("csm:res=1|3|1").find("occurs twice"), std::string::npos);
  EXPECT_NE(reason("csm:res=").find("empty value"), std::string::npos);
  EXPECT_NE(reason("csm:res=1..2/x1").find("factor must be > 1"), std::string::npos);
  EXPECT_NE(reason("csm:bias=0..1/log4").find("A > 0"), std::string::npos);
  EXPECT_NE(reason("csm:bias=0..1/lin1").find("'lin1': need linN with N >= 2"), std::string::npos);
  EXPECT_NE(reason("csm:bias=1..2/log0").find("'log0': need logN with N >= 2"), std::string::npos);
  EXPECT_NE(reason("csm:bias=0.5..1").find("whole-number ends"), std::string::npos);
  EXPECT_NE(reason("csm:res=1..1000000").find("more than 4096 values"), std::string::npos);
  EXPECT_NE(reason("csm:res=1,res=2").find("given twice"), std::string::npos);
  EXPECT_NE(reason("csm:pcf").find("expected key=domain"), std::string::npos);
  EXPECT_NE(reason(":res=1").find("no technique name"), std::string::npos);
  EXPECT_NE(reason("csm:res=a..b/x2").find("not a number"), std::string::npos);
  // Found by review: this range looped forever (i <= LONG_MAX) before the counted loop; its
  // values coincide in double, so it is refused.
  EXPECT_NE(reason("csm:res=9223372036854775800..9223372036854775807").find("occurs twice"), std::string::npos);
  std::string list = "csm:res=0";
  for (int i = 1; i <= 4096; ++i) list += "|" + std::to_string(i);
  EXPECT_NE(reason(list).find("more than 4096 values"), std::string::npos);
}

TEST(ParamSpace, SizeSaturatesInsteadOfWrapping) {
  // Six keys of 4096 values: 2^72 points, which wrapped to 0 in size_t.
  std::string text = "csm:";
  for (char k = 'a'; k < 'g'; ++k) text += std::string(k == 'a' ? "" : ",") + k + "=1..4096";
  EXPECT_EQ(parse_param_space(text, "--space").size(), SIZE_MAX);
}

}  // namespace
}  // namespace shadowlab
