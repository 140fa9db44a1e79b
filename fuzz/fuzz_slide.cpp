// libFuzzer target: slide specs (--slide): spot, grid:amp=A,freq=F[,res=N]; file names are
// skipped (they would read whatever the fuzzer names). Bad input must be an InputError.
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/slide.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string spec(reinterpret_cast<const char*>(data), size);
  if (spec.find('.') != std::string::npos || spec.find('/') != std::string::npos) return 0;
  try {
    shadowlab::make_slide(spec, "--slide");
  } catch (const shadowlab::InputError&) {
  }
  return 0;
}
