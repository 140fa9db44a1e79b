// Cache-file writes: a write that fails names the file and the OS's reason, and leaves no
// temporary behind.
#include "core/cache_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "../test_paths.h"
#include "core/error.h"

namespace shadowlab {
namespace {

TEST(CacheFile, FailedWriteNamesTheOsReasonAndLeavesNoTemporary) {
  const std::string dir = test::binary_path("core/cache_file_fail");
  std::filesystem::remove_all(dir);
  // The folder exists, the file's own subfolder does not: opening the temporary fails (ENOENT).
  const std::string path = dir + "/missing_subfolder/ref.bin";
  try {
    write_file_atomically(dir, path, std::vector<char>(16, 'x'), "reference cache file");
    FAIL() << "the write should fail";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot write the reference cache file: No such file or directory"),
              std::string::npos)
        << what;
  }
  size_t left = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    (void)entry;
    ++left;
  }
  EXPECT_EQ(left, 0u);
}

}  // namespace
}  // namespace shadowlab
