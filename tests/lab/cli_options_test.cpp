// Small rules of the common options and the environment (lab/cli.h, lab/environment.h).
#include <gtest/gtest.h>

#include "core/error.h"
#include "lab/cli.h"
#include "lab/environment.h"

namespace shadowlab {
namespace cli_options_test {

TEST(CliOptions, MaxMemoryIsGigabytesOfTenToTheNinthBytes) {
  CommonOptions o;
  EXPECT_EQ(max_memory_bytes(o), 0u);  // no limit
  o.max_memory_gb = 2.5;
  EXPECT_EQ(max_memory_bytes(o), 2500000000u);
}

TEST(CliOptions, AnEmptyEnvironmentValueIsTheVariableUnset) {
  for (const char* name : {"SHADOWLAB_THREADS", "SHADOWLAB_ISA", "SHADOWLAB_SCALAR"}) {
    EXPECT_NO_THROW(check_environment_value(name, "")) << name;
    EXPECT_THROW(check_environment_value(name, "x"), InputError) << name;
  }
}

}  // namespace cli_options_test
}  // namespace shadowlab
