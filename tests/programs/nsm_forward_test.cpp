// nsm_forward (programs/nsm_forward.cpp): bad input is one line and exit code 2 before any work;
// the output file holds the library's forward pass, the same bytes at 1 and 2 threads.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "programs/run_process.h"
#include "techniques/nsm/nsm_network.h"
#include "techniques/nsm_weights_writer.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

using test::expect_clear_error;
using test::run;

// Each test writes its own copy: ctest runs the tests of this file as concurrent processes.
std::string nsm_tiny_weights_file(const std::string& name) {
  std::filesystem::create_directories(test::binary_path("nsm_forward"));
  const std::string path = test::binary_path("nsm_forward/" + name + ".nsmw");
  NsmArch a;
  nsm_named_arch("tiny", a);
  test::nsmw_save(path, test::nsmw_bytes(test::nsmw_draft(a, 9)));
  return path;
}

std::vector<char> nsm_output_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(NsmForwardMain, RefusesBadInputInOneLine) {
  const std::string w = nsm_tiny_weights_file("tiny_refused"), out = " --out " + test::binary_path("nsm_forward/bad");
  expect_clear_error("nsm_forward" + out, "--weights: required");
  expect_clear_error("nsm_forward --weights " + test::binary_path("nsm_forward") + out,
                     "not a regular file");
  const std::string notw = test::binary_path("nsm_forward/not.nsmw");
  std::ofstream(notw) << "NSMX and more bytes than the fixed parts";
  expect_clear_error("nsm_forward --weights " + notw + out, "magic");
  expect_clear_error("nsm_forward --weights " + w + " --precision f8" + out, "--precision");
  expect_clear_error("nsm_forward --weights " + w + " --input " + w + out, "needs --width");
  // The weights file as planes: its size is not 4 planes of 8 × 8 floats.
  expect_clear_error("nsm_forward --weights " + w + " --input " + w + " --width 8 --height 8" + out,
                     "fp32 are 1024");
}

TEST(NsmForwardMain, WritesTheLibrarysOutputAtAnyThreadCount) {
  const std::string w = nsm_tiny_weights_file("tiny_forward");
  const int W = 21, H = 13;
  std::vector<float> planes(size_t(4) * W * H);
  for (size_t i = 0; i < planes.size(); ++i) planes[i] = float(int(i * 37 % 101) - 50) / 25.0f;
  const std::string in = test::binary_path("nsm_forward/planes.f32");
  std::ofstream(in, std::ios::binary)
      .write(reinterpret_cast<const char*>(planes.data()), std::streamsize(planes.size() * 4));
  std::vector<std::vector<char>> got;
  for (const int threads : {1, 2}) {
    const std::string out = test::binary_path("nsm_forward/out" + std::to_string(threads));
    const auto r = run("nsm_forward --weights " + w + " --input " + in + " --width 21 --height 13 --threads " +
                       std::to_string(threads) + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    got.push_back(nsm_output_bytes(out + "/output.f32"));
  }
  EXPECT_EQ(got[0], got[1]);
  const NsmNetwork net = nsm_network(read_nsm_weights(w));
  std::vector<float> want(size_t(W) * H);
  nsm_forward(net, planes.data(), W, H, want.data());
  ASSERT_EQ(got[0].size(), want.size() * 4);
  EXPECT_EQ(std::memcmp(got[0].data(), want.data(), got[0].size()), 0);
}

}  // namespace
}  // namespace shadowlab
