#include "core/notes.h"

#include <cstdio>
#include <mutex>

namespace shadowlab {
namespace {

struct Store {
  std::mutex mutex;
  std::vector<std::string> lines;
};

Store& store() {
  static Store s;
  return s;
}

}  // namespace

void hold_note(const std::string& line) {
  Store& s = store();
  std::lock_guard<std::mutex> lock(s.mutex);
  // A bound on what a pathological input can make us hold; the first lines say what matters.
  if (s.lines.size() < 1000) s.lines.push_back(line);
}

std::vector<std::string> take_notes() {
  Store& s = store();
  std::lock_guard<std::mutex> lock(s.mutex);
  std::vector<std::string> out;
  out.swap(s.lines);
  return out;
}

void print_notes() {
  for (const std::string& line : take_notes()) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace shadowlab
