// nsm_forward: runs the Neural Shadow Mapping network (techniques/nsm/nsm_network.h) on feature
// planes read from a raw file (F planes of W × H little-endian fp32, plane after plane) or on
// random planes (--seed), and writes the output (W × H fp32) to --out DIR/output.f32. With
// --repeats N it times the forward pass (after one untimed warm-up) and prints the median with
// the multiply-adds, GMAC/s and activation bytes (docs/techniques/nsm.md, "Network and
// inference").
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include <nlohmann/json.hpp>

#include "core/input_file.h"
#include "core/isa.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "techniques/nsm/nsm_network.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line(
        "nsm_forward", "--weights FILE [--input FILE] [--width W --height H] [flags]");
    CommonOptions common;
    add_common_options(cl, common);
    std::vector<std::string> unused;
    for (const std::string& f : common_scene_flags())
      if (f != "--width" && f != "--height" && f != "--out") unused.push_back(f);
    mark_unused(cl, unused, "the network reads feature planes, not a scene");
    std::string weights, input, precision_name = "f32";
    int repeats = 0, seed = 1;
    bool dump = false;
    add_text(cl, "--weights", "FILE", "the network's .nsmw weights file (required)", weights);
    add_text(cl, "--input", "FILE",
             "raw feature planes: F planes of W x H little-endian fp32, plane after plane "
             "(default: random planes from --seed)",
             input);
    add_int(cl, "--seed", "N", "seed of the random planes without --input (default 1)", seed, 0,
            1 << 30);
    add_text(cl, "--precision", "P",
             "activation storage: f32, f16 or bf16, arithmetic in fp32 (default f32)",
             precision_name);
    add_int(cl, "--repeats", "N",
            "time N forward passes after one untimed warm-up and print the median (default 0: "
            "one untimed pass)",
            repeats, 0, 1000);
    bool layers = false;
    add_switch(cl, "--layers",
               "with --repeats: also print each pass's median time, multiply-adds and the bytes it "
               "reads and stores (the supplemental's Tables 2/3)",
               layers);
    add_switch(cl, "--dump",
               "also write every stored activation tensor to DIR/tensors/NAME.f32 ([y][x][c] "
               "fp32) with its shape in DIR/tensors.json (for the per-pass check against PyTorch)",
               dump);
    if (!parse_command_line(cl, argc, argv)) return 0;
    if (weights.empty()) throw InputError("--weights", "required (a .nsmw file)");
    NsmPrecision precision = NsmPrecision::f32;
    if (precision_name == "f16") precision = NsmPrecision::f16;
    else if (precision_name == "bf16") precision = NsmPrecision::bf16;
    else if (precision_name != "f32")
      throw InputError("--precision", "expected f32, f16 or bf16, got '" + precision_name + "'");
    if (!input.empty() && (!common.width || !common.height))
      throw InputError("--input", "needs --width and --height (the planes' size)");
    const int W = common.width.value_or(1024), H = common.height.value_or(768);
    const NsmWeights w = read_nsm_weights(weights);
    const int F = w.arch.features;
    const size_t plane = size_t(W) * H;
    std::vector<float> planes(plane * F);
    if (!input.empty()) {
      InputFile probe(input, kImageFileLimit);
      if (probe.size() != planes.size() * 4)
        throw InputError(input, "is " + std::to_string(probe.size()) + " bytes; " +
                                    std::to_string(F) + " planes of " + std::to_string(W) + " x " +
                                    std::to_string(H) + " fp32 are " +
                                    std::to_string(planes.size() * 4));
      const std::vector<unsigned char> bytes = read_input_bytes(input, kImageFileLimit);
      if (bytes.size() != planes.size() * 4) throw InputError(input, "changed size while read");
      std::memcpy(planes.data(), bytes.data(), bytes.size());
      for (size_t i = 0; i < planes.size(); ++i)
        if (!std::isfinite(planes[i]))
          throw InputError(input, "value " + std::to_string(i) + " is not finite");
    } else {
      std::mt19937 rng{uint32_t(seed)};
      std::normal_distribution<float> n(0.0f, 1.0f);
      for (int f = 0; f < F; ++f)
        for (size_t i = 0; i < plane; ++i)
          planes[size_t(f) * plane + i] = w.mean[size_t(f)] + w.std[size_t(f)] * n(rng);
    }
    RunOutputs outputs(common.out, "--out");
    const NsmNetwork net = nsm_network(w);
    std::vector<float> out(plane);
    NsmForwardStats stats;
    nlohmann::json index = nlohmann::json::array();
    NsmTensorSink sink = nullptr;
    if (dump) {
      const std::string folder = outputs.subfolder("tensors");
      sink = [&index, folder](const std::string& name, const NsmTensor& t) {
        std::string b(size_t(t.w) * t.h * t.c * 4, '\0');
        for (int y = 0; y < t.h; ++y)
          std::memcpy(b.data() + size_t(y) * t.w * t.c * 4, t.px(y, 0), size_t(t.w) * t.c * 4);
        write_text_file(folder + "/" + name + ".f32", b);
        index.push_back({{"name", name}, {"height", t.h}, {"width", t.w}, {"channels", t.c}});
      };
    }
    nsm_forward(net, planes.data(), W, H, out.data(), precision, &stats, sink);
    if (dump) write_text_file(outputs.dir() + "/tensors.json", index.dump(1) + "\n");
    std::printf("nsm_forward: %d levels, %dx%d (padded %dx%d), %d threads, %s kernels, %s storage\n",
                w.arch.levels, W, H, stats.padded_width, stats.padded_height, thread_count(),
                isa_name(process_isa()), nsm_precision_name(precision));
    std::printf("work: %.3f GMAC, activations %.1f MB\n", stats.macs * 1e-9,
                double(stats.activation_bytes) * 1e-6);
    if (repeats > 0) {
      std::vector<double> t;
      std::vector<std::vector<double>> pass_ms(stats.passes.size());
      for (int i = 0; i < repeats; ++i) {
        NsmForwardStats rs;
        const auto s = std::chrono::steady_clock::now();
        nsm_forward(net, planes.data(), W, H, out.data(), precision, &rs);
        t.push_back(ms_since(s));
        for (size_t p = 0; p < rs.passes.size(); ++p) pass_ms[p].push_back(rs.passes[p].ms);
      }
      const Stat st = stat_of(t);
      std::printf("forward: median %.2f ms  min %.2f  max %.2f  (%d repeats)  %.1f GMAC/s\n",
                  st.median, st.min, st.max, repeats, stats.macs * 1e-6 / st.median);
      if (layers) {
        std::printf("%-10s %5s %9s %9s %9s %9s %8s %8s\n", "pass", "level", "ms", "GMAC",
                    "read MB", "store MB", "GMAC/s", "GB/s");
        for (size_t p = 0; p < stats.passes.size(); ++p) {
          const NsmPassStats& ps = stats.passes[p];
          const double ms = median(pass_ms[p]);
          const double mb = double(ps.bytes_read + ps.bytes_written) * 1e-6;
          std::printf("%-10s %5d %9.2f %9.3f %9.1f %9.1f %8.1f %8.1f\n", ps.name.c_str(), ps.level,
                      ms, ps.macs * 1e-9, double(ps.bytes_read) * 1e-6,
                      double(ps.bytes_written) * 1e-6, ms > 0 ? ps.macs * 1e-6 / ms : 0.0,
                      ms > 0 ? mb / ms : 0.0);
        }
      }
    }
    std::string bytes(out.size() * 4, '\0');
    std::memcpy(bytes.data(), out.data(), bytes.size());
    write_text_file(outputs.dir() + "/output.f32", bytes);
    outputs.commit();
    std::printf("wrote %s/output.f32\n", common.out.c_str());
    return 0;
  });
}
