// libFuzzer target: technique specs ("name:key=value,…") and spec lists, through the parser and
// every typed accessor the techniques use. Bad input must be an InputError, never a crash.
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    shadowlab::spec_list_items(text, "--techniques");  // the flags' lists: empty items named
  } catch (const shadowlab::InputError&) {
  }
  try {
    for (const std::string& item : shadowlab::split_spec_list(text)) {
      const shadowlab::Spec s = shadowlab::parse_spec(item, "--technique");
      shadowlab::SpecReader r(s, "--technique");
      r.get_int("res", 512, 1, 8192);
      r.get_double("bias", 0.01, 0.0, 1e3);
      r.get_bool("fp32", false);
      r.get_choice("depth", "f32", {"f32", "16", "8", "8cubic"});
      r.reject_unknown();
    }
  } catch (const shadowlab::InputError&) {
  }
  return 0;
}
