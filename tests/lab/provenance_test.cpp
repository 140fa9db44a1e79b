// The recorded command's editing (lab/provenance.h): the flags a merge or a repeat drops.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lab/provenance.h"

namespace shadowlab {
namespace provenance_test {

using Args = std::vector<std::string>;

TEST(Provenance, CommandWithoutDropsTheFlagsAndTheirValuesInBothSpellings) {
  const Args args{"sweep", "--out", "dir", "--scene", "default", "--shard=2/4", "--threads", "2"};
  EXPECT_EQ(command_without(args, {"--out", "--shard", "--threads"}), (Args{"sweep", "--scene", "default"}));
  EXPECT_EQ(command_without(args, {}), args);
  // A flag as the last word has no value to drop with it; a value equal to a flag name is a value.
  EXPECT_EQ(command_without(Args{"a", "--out"}, {"--out"}), (Args{"a", "--out"}));
  EXPECT_EQ(command_without(Args{"--scene", "--out", "b"}, {"--scene"}), (Args{"b"}));
}

}  // namespace provenance_test
}  // namespace shadowlab
