// The experiment executables end to end: bad input gives one line on stderr naming the flag or
// file and exit code 2; good input writes the promised files.
#include <gtest/gtest.h>

#include <map>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../test_paths.h"
#include "programs/run_process.h"
#include "core/image_io.h"
#include "lab/contact_sheet.h"

namespace shadowlab {
namespace {

using test::ProcResult;
using test::expect_clear_error;
using test::run;
using test::run_env;

TEST(Mains, BadInputIsOneLineAndExitCodeTwo) {
  const std::string out = test::binary_path("bad_input_out");
  expect_clear_error("render --technique csm --out " + out + " --bogus", "--bogus: unknown flag");
  expect_clear_error("render --technique nosuch --out " + out, "unknown technique 'nosuch'");
  expect_clear_error("render --technique csm:res=0 --out " + out, "res");
  expect_clear_error("render --technique csm --out " + out + " --width 0", "--width");
  expect_clear_error("render --technique csm --out " + out + " --width 99999999", "--width");
  expect_clear_error("render --technique csm --out " + out + " --threads 0", "--threads");
  expect_clear_error("render --technique csm --out " + out + " --scene /no/such/model.obj",
                     "/no/such/model.obj");
  expect_clear_error("render --technique csm --out " + out + " --scene nosuchscene", "nosuchscene");
  expect_clear_error("render --technique csm --out " + out + " --light-radius -1", "--light-radius");
  expect_clear_error("resolution_sweep --resolutions 128,0 --out " + out, "--resolutions");
  expect_clear_error("resolution_sweep --spp abc --out " + out, "--spp");
  expect_clear_error("resolution_sweep --plot /no/such/folder/p.svg --out " + out, "--plot");
  expect_clear_error("resolution_sweep --sheet colour --out " + out, "--sheet: expected mask or shaded");
  expect_clear_error("render --technique csm --out " + out + " --scene /no/such/scene.json",
                     "/no/such/scene.json");
  expect_clear_error("render --technique csm --out " + out + " --scene /no/such/model.glb",
                     "/no/such/model.glb");
  expect_clear_error("render --technique csm --out " + out + " --camera 1", "--camera");
  expect_clear_error("metric /no/such/test.exr /no/such/ref.exr", "/no/such/test.exr");
  expect_clear_error("metric only_one.exr", "two files");
  expect_clear_error("raster_bench --cull sideways", "--cull");
  expect_clear_error("raster_bench --repeats 3", "--repeats");
  expect_clear_error("raster_bench --res 0", "--res");
  expect_clear_error("raster_bench --only everything", "--only");
  expect_clear_error("raster_bench --scaling --threads 1", "--scaling");
}

// Every experiment takes the common flags; one it does not use is named in its --help and is a
// one-line error with the reason, never silently ignored (stability, metric and depth_precision
// used to call --scene unknown; projector_masking ignored --light-radius and --max-memory, the
// benchmarks --out). render's --out defaults to out/render like every other experiment's.
TEST(Mains, UnusedCommonFlagsAreNamedInHelpAndRejected) {
  const struct { const char* cmd; const char* flag; } cases[] = {
      {"stability --scene default", "--scene"},
      {"stability --out x", "--out"},
      {"stability --no-alpha", "--no-alpha"},  // a switch, last on the line
      {"metric a.exr b.exr --eye 1,2,3", "--eye"},
      {"depth_precision --scene default", "--scene"},
      {"depth_precision --light-radius 0", "--light-radius"},
      {"projector_masking --light-radius 0.1", "--light-radius"},
      {"projector_masking --max-memory 4", "--max-memory"},
      {"projector_masking --slide spot", "--slide"},
      {"raster_bench --out x", "--out"},
      {"technique_bench --max-memory 3", "--max-memory"},
  };
  for (const auto& c : cases) {
    expect_clear_error(c.cmd, std::string(c.flag) + ": is not used by this experiment: ");
    const std::string prog = std::string(c.cmd).substr(0, std::string(c.cmd).find(' '));
    const ProcResult h = run(prog + " --help");
    EXPECT_EQ(h.exit_code, 0) << prog;
    const size_t at = h.out.find("common flags not used here");
    ASSERT_NE(at, std::string::npos) << prog;
    EXPECT_NE(h.out.find(std::string(" ") + c.flag, at), std::string::npos) << prog << " " << c.flag;
  }
  // The flags they do use still work: stability and depth_precision take --threads (their
  // runs are covered elsewhere; here only that parsing gets past it to --help).
  EXPECT_EQ(run("stability --threads 1 --help").exit_code, 0);
  EXPECT_EQ(run("depth_precision --width 64 --help").exit_code, 0);
}

// The CLI11 layer's own errors come out in shadowlab's one-line form, naming the flag.
TEST(Mains, CommandLineErrorsNameTheFlag) {
  const std::string out = test::binary_path("cli_errors_out");
  const std::string base = "render --technique csm:res=16 --width 16 --height 12 --repeats 1 --out " + out;
  expect_clear_error(base + " --width 32", "--width: given twice");
  expect_clear_error(base + " --no-cache --no-cache", "--no-cache: given twice");
  expect_clear_error(base + " --no-cache=1", "--no-cache: takes no value");
  expect_clear_error(base + " --eye", "--eye: expects a value X,Y,Z");
  expect_clear_error(base + " --bogus=3", "--bogus: unknown flag");
  expect_clear_error(base + " stray", "stray: unexpected argument");
  expect_clear_error(base + " --fov 0x10", "--fov: expected a number, got '0x10'");
  expect_clear_error("technique_bench --repeats 2", "--repeats: 2 is outside [3, 100000]");
  // Found by use: a spec's own res was overridden by --res without a word.
  expect_clear_error("technique_bench --techniques csm,cmsm:res=256",
                     "--techniques: 'cmsm:res=256': give the resolution with --res");
  // Found by review: a flag taken as the previous flag's value, values on switches (also the
  // ones run_main answers), single-dash words, a leftover "--", coordinates beyond float.
  expect_clear_error("render --technique csm --out --no-alpha", "--out: expects a value, got the flag '--no-alpha'");
  expect_clear_error(base + " --no-alpha=true", "--no-alpha: takes no value");
  expect_clear_error("render --version=x", "--version: takes no value");
  expect_clear_error(base + " -j", "-j: unknown flag");
  expect_clear_error(base + " --", "--: unexpected argument");
  expect_clear_error(base + " --eye 1e39,0,0", "--eye: 1e39 is outside float's range");
  expect_clear_error("metric a.exr b.exr --max-memory", "--max-memory: is not used by this experiment");
  // A value may start with '-' (a negative coordinate), in both spellings.
  for (const char* eye : {" --eye -1,2.5,3", " --eye=-1,2.5,3"}) {
    const ProcResult r = run(base + eye);
    EXPECT_EQ(r.exit_code, 0) << eye << "\n" << r.err;
  }
  // --help lists every flag the program takes, with its placeholder.
  const ProcResult h = run("render --help");
  ASSERT_EQ(h.exit_code, 0);
  for (const char* f : {"--scene S", "--width W", "--eye X,Y,Z", "--technique SPEC", "--repeats N",
                        "--no-cache", "--ambient A", "--out DIR", "--max-memory GB", "--version"})
    EXPECT_NE(h.out.find(f), std::string::npos) << f;
}

// docs/command_line.md is every experiment's --help (generated by docs/command_line.sh): the
// documented flags are exactly the programs' own.
TEST(Mains, CommandLineDocEqualsEveryHelp) {
  std::ifstream f(test::source_path("docs/command_line.md"));
  ASSERT_TRUE(f) << "docs/command_line.md missing";
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  const std::string registry_marker = "techniques (a layout letter";
  int programs = 0;
  for (size_t at = doc.find("\n## "); at != std::string::npos; at = doc.find("\n## ", at + 1)) {
    const std::string name = doc.substr(at + 4, doc.find('\n', at + 4) - (at + 4));
    const size_t open = doc.find("```\n", at);
    const size_t close = doc.find("\n```", open + 4);
    ASSERT_NE(close, std::string::npos) << name;
    const std::string block = doc.substr(open + 4, close - (open + 4) + 1);
    const bool registry = name.rfind("The technique registry", 0) == 0;
    const ProcResult h = run(std::string(registry ? "render" : name) + " --help");
    ASSERT_EQ(h.exit_code, 0) << name;
    const size_t cut = h.out.find(registry_marker);
    ASSERT_NE(cut, std::string::npos) << name;
    const std::string expected = registry ? h.out.substr(cut) : h.out.substr(0, cut);
    EXPECT_EQ(block, expected) << name << ": run bash docs/command_line.sh";
    ++programs;
  }
  // One section per file of programs/ (each is one program) and one for the registry.
  int sources = 0;
  for (const auto& e : std::filesystem::directory_iterator(test::source_path("programs")))
    if (e.path().extension() == ".cpp") ++sources;
  EXPECT_EQ(programs, sources + 1);
}

TEST(Mains, RenderOutDefaultsToOutRender) {
  const std::string dir = test::binary_path("render_default_out");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const ProcResult r =
      run_env("cd " + dir + " &&", "render --technique csm:res=64 --width 32 --height 24 --repeats 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/render/mask.exr"));
  EXPECT_NE(r.out.find("wrote out/render/mask.exr"), std::string::npos) << r.out;
}

TEST(Mains, RenderWritesMaskTexelsAndTiming) {
  const std::string out = test::binary_path("render_out");
  std::filesystem::remove_all(out);
  const ProcResult r = run("render --technique csm:res=64 --width 64 --height 48 --repeats 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"mask.exr", "mask.png", "texel.exr", "timing.json"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  // The metric of a mask against itself is perfect, and --json carries every key.
  const ProcResult m = run("metric " + out + "/mask.exr " + out + "/mask.exr --texels " + out +
                    "/texel.exr --json");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const nlohmann::json j = nlohmann::json::parse(m.out);
  for (const char* k : {"c10", "c50", "c90", "dark", "lit", "acne", "noise", "ssim"})
    EXPECT_DOUBLE_EQ(j.at(k).get<double>(), 1.0) << k;
  EXPECT_DOUBLE_EQ(j.at("rmse").get<double>(), 0.0);
  // A 64² map seen by 64×48 pixels gives texels shared by several pixels: detail < 1, and the
  // total is the mean of fidelity (1), aesthetics (1) and detail (no timings given).
  const double detail = j.at("detail").get<double>();
  EXPECT_GT(detail, 0.0);
  EXPECT_LT(detail, 1.0);
  EXPECT_NEAR(j.at("total").get<double>(), (2.0 + detail) / 3.0, 1e-6);
  EXPECT_TRUE(j.contains("psnr"));
}

std::string file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The pixels of a mask or texel EXR as bytes (the headers carry provenance: date, threads and
// command differ from run to run, the pixels must not).
// "" when the file does not exist.
std::string mask_bytes(const std::string& path) {
  if (!std::filesystem::exists(path)) return "";
  const ImageF m = read_exr_mask(path);
  return std::string(reinterpret_cast<const char*>(m.data.data()), m.data.size() * sizeof(float));
}
std::string texel_bytes(const std::string& path) {
  if (!std::filesystem::exists(path)) return "";
  const ImageU32 t = read_exr_texels(path);
  return std::string(reinterpret_cast<const char*>(t.data.data()), t.data.size() * sizeof(uint32_t));
}

// A CSV without its leading "# provenance {...}" lines (checked to be there).
std::string csv_body(const std::string& path) {
  std::string csv = file_bytes(path);
  EXPECT_EQ(csv.rfind("# provenance {", 0), 0u) << path;
  while (csv.rfind("#", 0) == 0) csv.erase(0, csv.find('\n') + 1);
  return csv;
}

// A whole `render` (camera pass, technique, EXR writing) gives identical files for 1, 2 and 7
// threads, for a shadow map and for the soft Embree reference.
TEST(Mains, RenderIsIdenticalForOneTwoAndSevenThreads) {
  for (const std::string spec : {"csm:res=128,pcf=3", "rt:spp=8"}) {
    std::vector<std::string> masks, texels;
    for (int threads : {1, 2, 7}) {
      const std::string out = test::binary_path("render_threads_" + std::to_string(threads));
      std::filesystem::remove_all(out);
      const ProcResult r = run("render --technique " + spec + " --width 120 --height 90 --repeats 1 "
                               "--no-cache --threads " + std::to_string(threads) + " --out " + out);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      masks.push_back(mask_bytes(out + "/mask.exr"));
      texels.push_back(texel_bytes(out + "/texel.exr"));
    }
    ASSERT_FALSE(masks[0].empty());
    EXPECT_EQ(masks[0], masks[1]) << spec;
    EXPECT_EQ(masks[0], masks[2]) << spec;
    EXPECT_EQ(texels[0], texels[1]) << spec;
    EXPECT_EQ(texels[0], texels[2]) << spec;
  }
}

// The scalar paths (SHADOWLAB_SCALAR=1) and the SIMD ones give identical files for a whole
// render (camera pass, map render, and the lookup kernels: receivers, one-tap and N×N compare
// on the cube, tetrahedral and projector layouts, the moment maps' per-lane filters), on the
// default scene and on an OBJ.
TEST(Mains, ScalarAndSimdRasterPathsGiveIdenticalRenders) {
  std::vector<std::string> scenes = {"default"};
  scenes.push_back(test::assets_dir() + "/bunny/stanford-bunny.obj");
  const std::vector<std::string> all = {"csm:res=512,pcf=3", "csm:res=256", "tsm:res=256",
                                        "tsm:res=256,slope=3,bias=0.002", "tsm:res=256,pcf=5",
                                        "psm:res=256 --slide spot", "psm:res=256,pcf=3 --slide spot",
                                        "cvsm:res=256", "tvsm:res=256,fp32=1", "tesm:res=256",
                                        "cvsm:res=256,maxdepth_eps=0.05,bleed=0.2", "cesm:res=256,c=80"};
  // The bunny (69k triangles, whose OBJ parse dominates under the sanitizers) with one spec of
  // each layout and filter kind; the default scene with all of them.
  const std::vector<std::string> some = {"csm:res=512,pcf=3", "tsm:res=256,pcf=5",
                                         "psm:res=256 --slide spot", "cvsm:res=256", "tesm:res=256"};
  for (const std::string& scene : scenes)
  for (const std::string& spec : scene == "default" ? all : some) {
    std::vector<std::string> masks, texels;
    for (const char* env : {"SHADOWLAB_SCALAR=1 ", "SHADOWLAB_SCALAR=0 "}) {
      const std::string out = test::binary_path(std::string("render_path_") + env[17]);
      std::filesystem::remove_all(out);
      const std::string cmd = std::string(env) + SHADOWLAB_BINARY_DIR + "/programs/render --scene " +
                              scene + " --technique " + spec + " --width 200 --height 150 "
                              "--repeats 1 --out " + out + " >/dev/null 2>&1";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      masks.push_back(mask_bytes(out + "/mask.exr"));
      texels.push_back(texel_bytes(out + "/texel.exr"));
    }
    ASSERT_FALSE(masks[0].empty());
    EXPECT_EQ(masks[0], masks[1]) << scene << " " << spec;
    EXPECT_EQ(texels[0], texels[1]) << scene << " " << spec;
  }
}

// Width and height of a PNG from its IHDR chunk (big-endian at bytes 16 and 20); 0 if unreadable.
std::pair<int, int> png_size(const std::string& path) {
  const std::string b = file_bytes(path);
  if (b.size() < 24 || b.compare(1, 3, "PNG") != 0) return {0, 0};
  auto be32 = [&](size_t i) {
    return int((uint32_t(uint8_t(b[i])) << 24) | (uint32_t(uint8_t(b[i + 1])) << 16) |
               (uint32_t(uint8_t(b[i + 2])) << 8) | uint32_t(uint8_t(b[i + 3])));
  };
  return {be32(16), be32(20)};
}

// Projector flags (lab/cli.h apply_projector_flags): each misuse is one line naming
// its flag, exit code 2.
TEST(Mains, ProjectorBadInputIsOneLineAndExitCodeTwo) {
  const std::string out = test::binary_path("bad_projector_out");
  const std::string base = "render --width 32 --height 24 --repeats 1 --out " + out;
  expect_clear_error(base + " --technique csm --projector-pos 0,1,0", "--projector-pos");
  expect_clear_error(base + " --technique csm --projector-fov 30", "--projector-fov");
  expect_clear_error(base + " --technique csm --slide nosuch", "--slide");
  expect_clear_error(base + " --technique psm", "--technique");
  expect_clear_error(base + " --technique csm --slide spot --light-radius 0.1", "--light-radius");
  expect_clear_error(base + " --technique csm --slide spot --projector-target 0.9,2.7,-0.4",
                     "--projector-target");  // the default scene's light: target == position
  expect_clear_error(base + " --technique csm --slide /no/such/slide.png", "/no/such/slide.png");
  // A value outside a numeric flag's range is refused naming the range: the projector's field of
  // view is [0.1°, 169°], the memory budget up to 1e6 GB.
  expect_clear_error(base + " --technique csm --slide spot --projector-fov 169.5",
                     "--projector-fov: 169.5 is outside [0.1, 169]");
  expect_clear_error(base + " --technique csm --max-memory 2e6", "--max-memory: 2e6 is outside [1e-06, 1000000]");
}

// Every render writes the shaded image; without a projector, lit floor pixels are brighter
// than shadowed ones of the same material (the mask enters the shading).
TEST(Mains, RenderWritesShadedImagesForPointLights) {
  const std::string out = test::binary_path("render_shaded_out");
  std::filesystem::remove_all(out);
  const ProcResult r = run("render --scene default --technique csm:res=256 --width 64 --height 48 "
                           "--repeats 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(png_size(out + "/shaded.png"), std::make_pair(64, 48));
  const ImageF shaded = read_exr_rgb(out + "/shaded.exr");
  ASSERT_EQ(shaded.width, 64);
  float lo = 1e9f, hi = -1e9f;
  for (float v : shaded.data) {
    ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GT(hi, 4 * std::max(lo, 0.01f));
}

// A projector render writes the shaded image as linear EXR and sRGB PNG at the image size.
TEST(Mains, RenderWithSlideWritesShadedImages) {
  const std::string out = test::binary_path("render_projector_out");
  std::filesystem::remove_all(out);
  const ProcResult r = run("render --scene default --slide grid:amp=1,freq=4 --technique psm:res=128 "
                           "--width 64 --height 48 --repeats 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"mask.exr", "mask.png", "texel.exr", "timing.json", "shaded.exr", "shaded.png"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  EXPECT_EQ(png_size(out + "/shaded.png"), std::make_pair(64, 48));
  const ImageF shaded = read_exr_rgb(out + "/shaded.exr");
  ASSERT_EQ(shaded.width, 64);
  ASSERT_EQ(shaded.height, 48);
  // Linear values: non-negative; the projector lights some pixels above the ambient-only level
  // (ambient 0.1 × albedo ≤ 0.1) and leaves others at it.
  float lo = 1e30f, hi = -1e30f;
  for (float v : shaded.data) {
    ASSERT_GE(v, 0.0f);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GT(hi, 0.2f);
  EXPECT_LE(lo, 0.1f);
}

TEST(Mains, QuickSweepPrintsReferenceRowOfOnes) {
  const std::string out = test::binary_path("sweep_out");
  const std::string plot = test::binary_path("sweep_plot.svg");
  std::filesystem::remove(out + "/contact_sheet.png");
  std::filesystem::remove(plot);
  const ProcResult r = run("resolution_sweep --quick --width 96 --height 72 --spp 16 --repeats 1 "
                    "--resolutions 32,256 --no-cache --flip-map --out " + out + " --plot " + plot);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("RT 16spp            1.000  1.000  1.000  1.000  1.000  1.000  1.000   1.000"),
            std::string::npos) << r.out;
  // The reference's FLIP against itself is 0 (the column after total).
  EXPECT_NE(r.out.find("1.000 0.0000"), std::string::npos) << r.out;
  // --flip-map: each row's error map of its shaded image, the reference's all zero.
  for (const char* f : {"reference_flip.exr", "reference_flip.png", "csm_32_flip.exr", "csm_256_flip.png"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  const ImageF ref_flip = read_exr_mask(out + "/reference_flip.exr");
  for (float v : ref_flip.data) ASSERT_EQ(v, 0.0f);
  const ImageF flip32 = read_exr_mask(out + "/csm_32_flip.exr");
  EXPECT_GT(*std::max_element(flip32.data.begin(), flip32.data.end()), 0.0f);
  EXPECT_NE(r.out.find("CSM 32"), std::string::npos);
  EXPECT_NE(r.out.find("CSM 256"), std::string::npos);
  for (const char* f : {"sweep.csv", "sweep.json", "reference_mask.exr", "csm_256_mask.exr"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  EXPECT_NE(r.out.find("contact_sheet.png"), std::string::npos) << r.out;
  // The contact sheet: one row (CSM), columns REF, 32, 256 of 96×72 masks (no downscale), each
  // with its total score labelled under it (11 characters, "total 0.xyz").
  const auto [w, h] = png_size(out + "/contact_sheet.png");
  const std::vector<std::vector<std::string>> captions = {{"total 0.000", "total 0.000"}};
  const ContactSheetLayout l = contact_sheet_layout({"CSM"}, {"32", "256"}, 96, 72, true, {}, &captions);
  EXPECT_EQ(l.factor, 1);
  EXPECT_EQ(w, l.width);
  EXPECT_EQ(h, l.height);
  // The plot: both rows in each of the three panels (time, time, bytes), not the reference.
  const std::string svg = file_bytes(plot);
  ASSERT_FALSE(svg.empty());
  // A file output outside --out has the permissions any new file gets: rw for all the umask allows.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(unsigned(std::filesystem::status(plot).permissions() & std::filesystem::perms::all),
            unsigned(0666 & ~mask));
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find(">CSM 32</text>"), std::string::npos);
  EXPECT_NE(svg.find(">CSM 256</text>"), std::string::npos);
  EXPECT_EQ(svg.find("RT 16spp"), std::string::npos);
  size_t markers = 0;
  for (size_t p = svg.find("class=\"pt\""); p != std::string::npos; p = svg.find("class=\"pt\"", p + 1))
    ++markers;
  EXPECT_EQ(markers, 6u);
  EXPECT_NE(svg.find("map bytes touched"), std::string::npos);
}

// Every input is checked before the first expensive step (the camera pass and the reference),
// and nothing is written: empty, doubled and duplicate list items, a projector technique without
// a projector, a plot path that is a folder.
TEST(Mains, SweepInputsAreCheckedBeforeAnyWork) {
  const std::string out = test::binary_path("sweep_checks_out");
  std::filesystem::remove_all(out);
  const std::string base = "resolution_sweep --quick --out " + out;
  expect_clear_error(base + " --techniques ''", "--techniques: is empty");
  expect_clear_error(base + " --techniques ,,", "--techniques: ',,': item 1 of 3 is empty (a comma before the first spec)");
  expect_clear_error(base + " --techniques csm,,tsm", "--techniques: 'csm,,tsm': item 2 of 3 is empty (two commas in a row)");
  expect_clear_error(base + " --techniques csm,", "--techniques: 'csm,': item 2 of 2 is empty (a comma after the last spec)");
  expect_clear_error(base + " --techniques csm,csm", "given twice");
  expect_clear_error(base + " --resolutions 64,64", "given twice");
  expect_clear_error(base + " --resolutions 64,", "--resolutions");
  expect_clear_error(base + " --techniques psm", "needs a slide projector");
  expect_clear_error(base + " --plot " + test::binary_path(""), "is a folder");
  EXPECT_FALSE(std::filesystem::exists(out + "/sweep.csv"));
  EXPECT_FALSE(std::filesystem::exists(out + "/reference_mask.exr"));
}

// Numbers and lists are parsed strictly, and the raw spelling never reaches labels.
TEST(Mains, NumbersAndListsAreStrict) {
  const std::string out = test::binary_path("strict_out");
  const std::string base = "render --width 32 --height 24 --repeats 1 --out " + out;
  expect_clear_error(base + " --technique csm:res=+64", "'res' expects an integer");
  expect_clear_error(base + " --technique csm:bias=0x1p-3", "'bias' expects a number");
  expect_clear_error(base + " --technique 'csm:res= 64'", "'res' expects an integer");
  expect_clear_error(base + " --technique csm --eye 0,3,8,", "--eye");
  expect_clear_error(base + " --technique csm --slide grid:amp=1,amp=0.5,freq=2", "given twice");
  expect_clear_error(base + " --technique csm --slide grid:amp=1,freq=2,", "--slide");
  expect_clear_error(base + " --technique csm:res=99999", "outside [1, 8192]");
}

// One prefix per message: an error raised by the metric library in the metric program is not
// named twice.
TEST(Mains, ErrorsNameTheirSourceOnce) {
  const std::string a = test::binary_path("prefix_a"), b = test::binary_path("prefix_b");
  ASSERT_EQ(run("render --technique csm:res=16 --width 32 --height 24 --repeats 1 --out " + a).exit_code, 0);
  ASSERT_EQ(run("render --technique csm:res=16 --width 40 --height 24 --repeats 1 --out " + b).exit_code, 0);
  const ProcResult r = run("metric " + a + "/mask.exr " + b + "/mask.exr");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.find("metric: metric:"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.rfind("metric: ", 0), 0u) << r.err;
}

// A reference read from the cache was not timed: null times in JSON, empty CSV fields, and no
// performance score for the reference row (the table shows "-").
TEST(Mains, CachedReferenceTimesAreNull) {
  const std::string out = test::binary_path("cached_ref_out");
  const std::string cache = test::binary_path("cached_ref_cache");
  std::filesystem::remove_all(cache);  // the first run computes the reference
  const std::string cmd = "SHADOWLAB_CACHE=" + cache + " " + std::string(SHADOWLAB_BINARY_DIR) +
                          "/programs/resolution_sweep --quick --width 64 --height 48 --resolutions 32 --out " + out +
                          " >/dev/null 2>&1";
  // The reference row's line of sweep.csv (the line after the header).
  auto reference_line = [&] {
    const std::string csv = csv_body(out + "/sweep.csv");
    const size_t a = csv.find('\n') + 1;
    return csv.substr(a, csv.find('\n', a) - a);
  };
  // Its last n comma-separated cells.
  auto last_cells = [](const std::string& line, int n) {
    size_t at = line.size();
    for (int i = 0; i < n && at != std::string::npos && at > 0; ++i) at = line.rfind(',', at - 1);
    return at == std::string::npos ? line : line.substr(at + 1);
  };
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string computed = reference_line();
  ASSERT_EQ(std::system(cmd.c_str()), 0);  // second run: the reference comes from the cache
  // The work counts (the last 8 cells) read the same either way, formats included.
  EXPECT_EQ(last_cells(reference_line(), 8), last_cells(computed, 8)) << computed;
  const nlohmann::json j = nlohmann::json::parse(file_bytes(out + "/sweep.json"));
  EXPECT_TRUE(j["reference"]["from_cache"].get<bool>());
  EXPECT_TRUE(j["reference"]["shadow_ms"].is_null());
  EXPECT_FALSE(j["reference"].contains("performance"));
  EXPECT_TRUE(j["rows"][0]["shadow_ms"].is_number());
  const std::string csv = csv_body(out + "/sweep.csv");
  const std::string ref_line = csv.substr(csv.find('\n') + 1, csv.find('\n', csv.find('\n') + 1) - csv.find('\n') - 1);
  EXPECT_NE(ref_line.find("100.0000,,,,,1.000000"), std::string::npos) << ref_line;
}

// --suite hard: one sweep per scene in --out/SCENE/, a summary with each scene's fidelity and
// total and the mean and worst per setting, one CSV with a scene column over all four.
TEST(Mains, SuiteSweepsEveryScene) {
  const std::string out = test::binary_path("suite_out");
  std::filesystem::remove_all(out);
  const ProcResult r = run("resolution_sweep --suite hard --quick --width 48 --height 36 --spp 4 "
                           "--resolutions 32 --techniques csm,cvsm --no-cache --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("suite hard: 4 scenes"), std::string::npos) << r.out;
  for (const char* scene : {"grazing", "contact", "depth_range", "cluttered"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + scene + "/sweep.csv")) << scene;
    EXPECT_TRUE(std::filesystem::exists(out + "/" + scene + "/contact_sheet.png")) << scene;
  }
  std::istringstream csv(csv_body(out + "/sweep.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("scene,label,", 0), 0u) << line;
  std::map<std::string, int> rows;
  while (std::getline(csv, line)) ++rows[line.substr(1, line.find('"', 1) - 1)];
  EXPECT_EQ(rows.size(), 4u);
  for (const auto& [scene, n] : rows) EXPECT_EQ(n, 3) << scene;  // reference + 2 techniques
  // The summary's mean is the mean of the scene columns (checked on the first fidelity row).
  const size_t at = r.out.find("CSM 32", r.out.find("suite hard"));
  ASSERT_NE(at, std::string::npos);
  std::istringstream row(r.out.substr(at + 6, r.out.find('\n', at) - at - 6));
  double v[6];
  for (double& x : v) row >> x;
  EXPECT_NEAR(v[4], (v[0] + v[1] + v[2] + v[3]) / 4.0, 0.0015);
  EXPECT_NEAR(v[5], std::min({v[0], v[1], v[2], v[3]}), 1e-9);
  const nlohmann::json j = nlohmann::json::parse(file_bytes(out + "/sweep.json"));
  EXPECT_EQ(j["suite"], "hard");
  EXPECT_EQ(j["scenes"].size(), 4u);
  expect_clear_error("resolution_sweep --suite easy --out " + out, "--suite");
  expect_clear_error("resolution_sweep --suite hard --scene plane --out " + out, "--suite");
}

// Every CSV row has the header's field count when commas inside quotes are not separators: a
// spec with its own keys ("csm:pcf=3") puts commas into both the label and the spec.
TEST(Mains, SweepCsvQuotesFieldsWithCommas) {
  const std::string out = test::binary_path("csv_quote_out");
  const std::string cmd = std::string(SHADOWLAB_BINARY_DIR) +
                          "/programs/resolution_sweep --quick --width 64 --height 48 "
                          "--resolutions 32 --no-cache --techniques csm:pcf=3,bias=0.02 --out " +
                          out + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::istringstream csv(csv_body(out + "/sweep.csv"));
  auto fields = [](const std::string& line) {
    size_t n = 1;
    bool quoted = false;
    for (const char c : line) {
      if (c == '"') quoted = !quoted;
      n += c == ',' && !quoted;
    }
    return n;
  };
  std::string header, line;
  std::getline(csv, header);
  int rows = 0;
  while (std::getline(csv, line)) {
    EXPECT_EQ(fields(line), fields(header)) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2);  // the reference and csm at 32
}

// A cache folder that cannot be written: the reference is computed, used and written to --out,
// with one warning (it used to be computed, then the run failed with no mask written).
TEST(Mains, UnwritableCacheLosesNoWork) {
  const std::string blocker = test::binary_path("cache_blocker_file");
  std::ofstream(blocker) << "a file, not a folder";
  const std::string out = test::binary_path("unwritable_cache_out");
  std::filesystem::remove_all(out);
  const ProcResult r = run_env("SHADOWLAB_CACHE=" + blocker + "/cache",
                               "render --technique rt:spp=4 --width 64 --height 48 --out " + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out + "/mask.exr"));
  EXPECT_NE(r.err.find("not writable"), std::string::npos) << r.err;
}

// A write that fails part way (here a file-size limit of 4 KiB, as a full disk would) is an
// error naming the file, and leaves no truncated file under its name (a truncated texel.exr used
// to remain), nor any file of the failed run: its outputs appear all together or not at all.
TEST(Mains, FailedWritesLeaveNoTruncatedFiles) {
  const std::string out = test::binary_path("fsize_out");
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  const std::string cmd = "bash -c \"trap '' XFSZ; ulimit -f 4; exec " + std::string(SHADOWLAB_BINARY_DIR) +
                          "/programs/render --technique csm:res=64 --width 96 --height 72 --repeats 1 --out " +
                          out + "\" >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  // mask.exr (~2 KiB with its provenance attributes) fits under the 4 KiB limit; texel.exr
  // (~10 KiB) does not fit, so neither appears.
  EXPECT_FALSE(std::filesystem::exists(out + "/texel.exr"));
  EXPECT_FALSE(std::filesystem::exists(out + "/mask.exr"));
  EXPECT_TRUE(std::filesystem::is_empty(out));
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(out).parent_path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find("fsize_out.staging"), std::string::npos) << "temporary left: " << name;
  }
}

// A run that cannot fit in memory is refused before any work with the estimate (16384² used
// to run 33 s and end in std::bad_alloc, exit 1).
TEST(Mains, RunsThatCannotFitAreRefusedUpFront) {
  const std::string out = test::binary_path("memory_out");
  const ProcResult small = run("render --technique csm --width 64 --height 48 --repeats 1 --max-memory 0.0001 --out " + out);
  EXPECT_EQ(small.exit_code, 2);
  EXPECT_NE(small.err.find("--max-memory: this run needs about"), std::string::npos) << small.err;
  const ProcResult maps = run("render --technique cvsm:res=4096,blur=63 --width 64 --height 48 --max-memory 1 --out " + out);
  EXPECT_EQ(maps.exit_code, 2);
  EXPECT_NE(maps.err.find("maps 1.2 GB"), std::string::npos) << maps.err;  // 6·4102²·12 B
  // The machine's own limit: 16384² needs ~31 GB of image memory, more than a 24 GB machine has.
  const ProcResult huge = run("render --technique csm --width 16384 --height 16384 --out " + out);
  EXPECT_EQ(huge.exit_code, 2) << huge.err;
  EXPECT_NE(huge.err.find("--width: this run needs about"), std::string::npos) << huge.err;
  EXPECT_EQ(run("render --technique csm --width 64 --height 48 --repeats 1 --max-memory 1 --out " + out).exit_code, 0);
}

// --version and --list-techniques work on every program, before any other flag is read.
TEST(Mains, VersionAndTechniqueListEverywhere) {
  for (const char* prog : {"render", "metric", "resolution_sweep", "raster_bench", "stability"}) {
    const ProcResult v = run(std::string(prog) + " --version");
    EXPECT_EQ(v.exit_code, 0) << prog;
    EXPECT_NE(v.out.find(std::string(prog) + " (shadowlab) commit "), std::string::npos) << v.out;
    const ProcResult l = run(std::string(prog) + " --list-techniques");
    EXPECT_EQ(l.exit_code, 0) << prog;
    for (const char* name : {"rt", "csm", "tsm", "psm", "cvsm", "tvsm", "pvsm", "cesm", "tesm", "pesm"})
      EXPECT_NE(l.out.find(std::string("  ") + name + "  "), std::string::npos) << prog << " " << name;
  }
}

// flicker and penumbra: bad flags are one-line errors before any work; a small flicker run
// writes its three files.
TEST(Mains, FlickerAndPenumbraCheckTheirFlags) {
  const std::string out = test::binary_path("flicker_out");
  expect_clear_error("flicker --frames 1 --out " + out, "--frames");
  expect_clear_error("flicker --path camera-pan --jitter --out " + out, "--jitter");
  expect_clear_error("flicker --path zigzag --out " + out, "--path: unknown path 'zigzag'");
  expect_clear_error("flicker --techniques csm:res=64 --out " + out, "--techniques");
  expect_clear_error("flicker --step -1 --out " + out, "--step");
  expect_clear_error("penumbra --radii 0 --out " + out, "--radii");
  expect_clear_error("penumbra --scene foliage --out " + out, "--scene");
  expect_clear_error("penumbra --points 100000 --spp 1048576 --out " + out, "--spp: 100000 points");
  expect_clear_error("flicker --width 4096 --height 4096 --max-memory 1 --out " + out,
                     "--max-memory: this run needs about");
  const ProcResult r = run("flicker --techniques csm,rt --resolutions 64 --frames 3 --width 64 --height 48 --spp 4 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"flicker.csv", "flicker.json", "flicker_worst.png"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  const nlohmann::json j = test::read_json(out + "/flicker.json");
  EXPECT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][1]["excess"].get<double>(), 0.0);  // the reference's own row
}

TEST(Mains, AlphaFlagsAreChecked) {
  const std::string out = test::binary_path("alpha_flags_out");
  expect_clear_error("render --technique csm --alpha-cutoff 1.5 --out " + out, "--alpha-cutoff");
  expect_clear_error("render --technique csm --alpha-cutoff -0.1 --out " + out, "--alpha-cutoff");
  expect_clear_error("render --technique csm --alpha-cutoff 0.5 --no-alpha --out " + out, "--alpha-cutoff");
}

TEST(Mains, ProjectorMaskingPrintsTablesAndSheet) {
  const std::string out = test::binary_path("masking_out");
  std::filesystem::remove(out + "/contact_sheet.png");
  const ProcResult r = run("projector_masking --width 64 --height 48 --repeats 1 --levels 300 "
                           "--slides 'spot;grid:amp=1,freq=15' --technique psm:res=256 --no-cache --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // One table per measure; the full mesh's row compares it with itself.
  EXPECT_NE(r.out.find("SSIM against the full mesh"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("visible after contrast masking"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  full                     1.0000                 1.0000"), std::string::npos) << r.out;
  for (const char* f : {"masking.csv", "contact_sheet.png", "full_spot.png", "300_grid_amp_1_freq_15.png"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  expect_clear_error("projector_masking --slides 'spot;stripes' --out " + out, "--slides");
  expect_clear_error("projector_masking --scene default --out " + out, "--scene");
  expect_clear_error("projector_masking --levels 0 --out " + out, "--levels");
}

TEST(Mains, DepthPrecisionPrintsEveryFormatOnBothScenes) {
  const std::string out = test::binary_path("depth_out");
  const ProcResult r = run("depth_precision --width 64 --height 48 --repeats 1 --spp 4 "
                           "--csm csm:res=64 --psm psm:res=64 --no-cache --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* row : {"CSM:DEPTH=F32 64", "CSM:DEPTH=16 64", "CSM:DEPTH=8 64", "CSM:DEPTH=8CUBIC 64",
                          "PSM:DEPTH=F32 64", "PSM:DEPTH=8CUBIC 64"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  EXPECT_TRUE(std::filesystem::exists(out + "/default/sweep.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/projector/sweep.csv"));
  expect_clear_error("depth_precision --csm csm:depth=8 --out " + out, "--csm");
  expect_clear_error("depth_precision --psm tsm:res=64 --out " + out, "--psm");
}

}  // namespace
}  // namespace shadowlab
