// The programs and their input files: a FIFO, a folder or /dev/zero where a file is expected
// is one line and exit 2 (a FIFO without waiting for a writer, /dev/zero without reading it);
// the JSON files read back (--from, merge) refuse duplicate keys and nesting beyond
// kMaxJsonDepth the same way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/image_io.h"
#include "programs/run_process.h"
#include "fifo_feeder.h"
#include "test_paths.h"
#include "test_scratch.h"

namespace shadowlab {
namespace input_files_mains_test {

using test::expect_clear_error;

std::string scratch(const std::string& name) { return test::scratch_path("input_files_mains", name); }

std::string write_text(const std::string& name, const std::string& text) {
  return test::write_scratch_text("input_files_mains", name, text);
}

std::string reference_mask() {
  const std::string path = scratch("ref.exr");
  write_exr_mask(path, ImageF(8, 6, 1, 0.5f));
  return path;
}

// A blocking open of a FIFO waits for a writer (the feeder is one: the test is bounded on any
// code).
TEST(InputFilesMains, MetricRefusesAFifoWithoutWaiting) {
  const std::string ref = reference_mask();
  test::FifoFeeder fifo(scratch("test_fifo.exr"));
  ASSERT_TRUE(fifo.ok());
  expect_clear_error("metric " + fifo.path() + " " + ref, fifo.path() + ": is a FIFO, not a regular file");
  fifo.release();
}

// A folder given as an EXR is not a regular file (rather than "not an EXR file").
TEST(InputFilesMains, MetricNamesAFolderAsNotARegularFile) {
  const std::string ref = reference_mask();
  const std::string dir = scratch("folder.exr");
  std::filesystem::create_directories(dir);
  expect_clear_error("metric " + dir + " " + ref, dir + ": is a directory, not a regular file");
}

// --scene /dev/zero is refused before it is read (as an OBJ, without end).
TEST(InputFilesMains, SceneThatIsADeviceIsRefusedBeforeReading) {
  expect_clear_error("render --technique csm --width 16 --height 12 --out " + scratch("out_zero") +
                         " --scene /dev/zero",
                     "/dev/zero: is a character device, not a regular file");
}

TEST(InputFilesMains, FromAndMergeRefuseDuplicateKeys) {
  const std::string dup = write_text(
      "dup.json", R"({"provenance": {"program": "render", "program": "metric", "command": []}})");
  expect_clear_error("render --from " + dup,
                     dup + ": provenance.program: duplicate key in a JSON object (each key may appear once)");
  expect_clear_error("merge " + dup + " --out " + scratch("merged_dup"),
                     dup + ": provenance.program: duplicate key in a JSON object");
}

TEST(InputFilesMains, FromAndMergeRefuseDeepNesting) {
  const std::string deep = write_text("deep.json", "{\"provenance\": " + std::string(20000, '[') +
                                                       std::string(20000, ']') + "}");
  expect_clear_error("render --from " + deep, deep + ": JSON nesting deeper than 64 levels at provenance[0]");
  expect_clear_error("merge " + deep + " --out " + scratch("merged_deep"),
                     deep + ": JSON nesting deeper than 64 levels");
  const std::string dir = scratch("from_folder.json");
  std::filesystem::create_directories(dir);
  expect_clear_error("render --from " + dir, dir + ": is a directory, not a regular file");
}

}  // namespace input_files_mains_test
}  // namespace shadowlab
