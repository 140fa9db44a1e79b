// Input files (core/input_file.h): only regular files within their kind's limit reach a
// parser. A directory, a FIFO and a character device are refused by name before anything is
// read (a FIFO without waiting for a writer). non_regular_inputs_test.cpp: the readers built
// on it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"
#include "fifo_feeder.h"
#include "test_paths.h"
#include "test_scratch.h"

namespace shadowlab {
namespace input_file_test {

std::string scratch(const std::string& name) { return test::scratch_path("input_file", name); }

using test::input_error;

constexpr InputLimit kTiny{4, "a test file"};

TEST(InputFile, ReadsARegularFileWhole) {
  const std::string path = scratch("four.txt");
  std::ofstream(path, std::ios::binary).write("a\0b\n", 4);
  EXPECT_EQ(read_input_file(path, kTiny), std::string("a\0b\n", 4));
  EXPECT_EQ(read_input_bytes(path, kTiny), (std::vector<unsigned char>{'a', 0, 'b', '\n'}));
}

// One byte over the limit is refused, naming the size, the limit and the kind.
TEST(InputFile, OverTheLimitIsRefusedBeforeReading) {
  const std::string path = scratch("five.txt");
  std::ofstream(path, std::ios::binary) << "12345";
  EXPECT_EQ(input_error([&] { read_input_file(path, kTiny); }),
            path + ": is 5 bytes, over the limit of 4 bytes for a test file");
  EXPECT_EQ(format_byte_limit(kSceneFileLimit.bytes), "1 MiB");
  EXPECT_EQ(format_byte_limit(kModelFileLimit.bytes), "2 GiB");
  EXPECT_EQ(format_byte_limit(1536ull << 20), "1536 MiB");
}

TEST(InputFile, MissingFileSaysCannotOpen) {
  const std::string path = scratch("missing.txt");
  EXPECT_EQ(input_error([&] { read_input_file(path, kTiny); }),
            path + ": cannot open: No such file or directory");
}

TEST(InputFile, NonRegularFilesAreRefusedByKind) {
  const std::string dir = scratch("a_folder");
  std::filesystem::create_directories(dir);
  EXPECT_EQ(input_error([&] { read_input_file(dir, kModelFileLimit); }),
            dir + ": is a directory, not a regular file");
  EXPECT_EQ(input_error([&] { read_input_file("/dev/zero", kModelFileLimit); }),
            "/dev/zero: is a character device, not a regular file");
  test::FifoFeeder fifo(scratch("a_fifo"));
  ASSERT_TRUE(fifo.ok());
  EXPECT_EQ(input_error([&] { read_input_file(fifo.path(), kModelFileLimit); }),
            fifo.path() + ": is a FIFO, not a regular file");
}

}  // namespace input_file_test
}  // namespace shadowlab
