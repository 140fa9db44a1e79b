// The readers of images and caches (core/image_io.h, core/texture.h, core/cache_file.h) take
// only regular files: a directory, a FIFO or a device is refused by name (a FIFO without
// waiting for a writer), and for a cache it is a miss.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/cache_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/texture.h"
#include "fifo_feeder.h"
#include "test_paths.h"
#include "test_scratch.h"

namespace shadowlab {
namespace non_regular_inputs_test {

std::string scratch(const std::string& name) { return test::scratch_path("non_regular_inputs", name); }

using test::input_error;

// A folder given as an EXR is "not a regular file", not "not an EXR file" (OpenEXR's view of
// a folder's zero bytes); a FIFO is refused instead of waited on.
TEST(NonRegularInputs, ExrReadersRefuseAFolderAndAFifo) {
  const std::string dir = scratch("mask_folder.exr");
  std::filesystem::create_directories(dir);
  EXPECT_EQ(input_error([&] { read_exr_mask(dir); }), dir + ": is a directory, not a regular file");
  EXPECT_EQ(input_error([&] { read_exr_rgb(dir); }), dir + ": is a directory, not a regular file");
  EXPECT_EQ(input_error([&] { exr_image_size(dir); }), dir + ": is a directory, not a regular file");
  test::FifoFeeder fifo(scratch("mask_fifo.exr"));
  ASSERT_TRUE(fifo.ok());
  EXPECT_EQ(input_error([&] { read_exr_mask(fifo.path()); }),
            fifo.path() + ": is a FIFO, not a regular file");
  fifo.release();
}

TEST(NonRegularInputs, ImageReadersRefuseAFolder) {
  const std::string dir = scratch("texture_folder.png");
  std::filesystem::create_directories(dir);
  EXPECT_EQ(input_error([&] { load_texture8(dir); }), dir + ": is a directory, not a regular file");
  EXPECT_EQ(input_error([&] { image_file_size(dir); }), dir + ": is a directory, not a regular file");
}

// A cache path that is not a regular file is a miss (the cache is recomputed), not a hang.
TEST(NonRegularInputs, CacheReadOfANonRegularFileIsAMiss) {
  std::vector<char> bytes{'x'};
  const std::string dir = scratch("cache_folder");
  std::filesystem::create_directories(dir);
  EXPECT_FALSE(read_file_bytes(dir, 0, bytes));
  EXPECT_FALSE(read_file_bytes("/dev/zero", 0, bytes));
  test::FifoFeeder fifo(scratch("cache_fifo"));
  ASSERT_TRUE(fifo.ok());
  EXPECT_FALSE(read_file_bytes(fifo.path(), 0, bytes));
  fifo.release();
  const std::string path = scratch("cache.bin");
  std::ofstream(path, std::ios::binary) << "abc";
  ASSERT_TRUE(read_file_bytes(path, 3, bytes));
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "abc");
  EXPECT_FALSE(read_file_bytes(path, 4, bytes));  // shorter than the header: a miss
}

}  // namespace non_regular_inputs_test
}  // namespace shadowlab
