#pragma once
// What the Python module runs, in plain C++ (no Python types): each call takes the programs'
// flags as text and goes through the same parsing, checks and library functions as the program
// it mirrors (lab/*_command.h), so it accepts, refuses and computes the same.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "metric/shadow_metric.h"
#include "techniques/nsm/nsm_features.h"
#include "techniques/registry/technique.h"

namespace shadowlab::python {

// One field of a record (a table row, a dict): the value kinds Python receives.
struct Field {
  enum class Kind { none, number, integer, text } kind = Kind::none;
  std::string name;
  double number = 0.0;
  int64_t integer = 0;
  std::string text;
};
using Fields = std::vector<Field>;

struct PyScene {
  Scene scene;
  std::vector<std::string> flags;  // the common flags that built it, as a program takes them
};
struct PyGBuffer {
  GBuffer g;
  double camera_ms = 0.0;  // median of the camera pass's timed runs
};
struct PyResult {
  ShadowResult r;
  std::string spec;        // canonical spec text
  double camera_ms = 0.0;  // the GBuffer's camera pass
};
// Keeps a feature set alive while NumPy views of its planes exist.
struct FeatureOwner {
  std::shared_ptr<NsmFeatures> features;
};

// The scene the common flags describe (render's rules: a built-in name, an OBJ, glTF or scene
// file, the light, camera and projector overrides, the view check).
PyScene make_scene(const std::vector<std::string>& flags);
// The camera pass, timed over `repeats` runs; refuses a view that covers no pixel.
PyGBuffer make_gbuffer(const PyScene& s, int repeats);
// One technique (or the reference, rt:…) on the scene's GBuffer, as render runs it: the spec
// parsed and checked against the scene and the memory before any work.
PyResult render(const PyScene& s, const std::string& spec, const PyGBuffer& g, int repeats,
                bool cache, bool texels);
// The shaded picture of a result (render's shaded.exr), linear RGB.
ImageF shaded_image(const PyResult& r, const PyScene& s, const PyGBuffer& g, double ambient);
Fields result_times(const PyResult& r);
Fields result_work(const PyResult& r);
Fields result_faces(const PyResult& r);
// The metric of a test mask against a reference, the keys and order of `metric --json`.
Fields metric_fields(const ImageF& test, const ImageF& ref, const ImageU32* texels,
                     const double* shadow_ms, double fps);
// resolution_sweep's flags → its rows (reference first), the columns of sweep.csv. With --out,
// also the program's files (sweep.csv, sweep.json, contact_sheet.png, masks).
std::vector<Fields> resolution_sweep(const std::vector<std::string>& flags);
// tune's flags → one row per full-size evaluation, the columns of tune.csv; with --out, the
// program's files.
std::vector<Fields> tune(const std::vector<std::string>& flags);
// The NSM network's input planes for the spec (nsm_spec_features).
NsmFeatures nsm_features(const PyScene& s, const PyGBuffer& g, const std::string& spec,
                         bool every_candidate);
// The bytes of frame `frame` of the data set nsm_data's flags describe (its .nsmf file).
std::string nsm_frame(const std::vector<std::string>& flags, int frame);
// The split of every frame of that data set ("train", "val" or "test"), as its manifest lists.
std::vector<std::string> nsm_frame_splits(const std::vector<std::string>& flags);

}  // namespace shadowlab::python
