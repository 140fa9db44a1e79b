#include "core/spec.h"

#include <algorithm>

#include "core/error.h"
#include "core/parse_number.h"
#include "core/repeats.h"

namespace shadowlab {

Spec parse_spec(const std::string& text, const std::string& flag) {
  Spec spec;
  const size_t colon = text.find(':');
  spec.name = text.substr(0, colon);
  if (text.empty()) throw InputError(flag, "empty spec (expected NAME or NAME:key=value,...)");
  if (spec.name.empty()) throw InputError(flag, "no name before ':' in '" + text + "'");
  if (colon != std::string::npos) {
    const std::string rest = text.substr(colon + 1);
    size_t pos = 0;
    while (pos <= rest.size()) {
      const size_t comma = std::min(rest.find(',', pos), rest.size());
      const std::string item = rest.substr(pos, comma - pos);
      const size_t eq = item.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
        throw InputError(flag, "expected key=value in '" + text + "', got '" + item + "'");
      const std::string key = item.substr(0, eq);
      if (spec.params.count(key)) throw InputError(flag, "parameter '" + key + "' given twice");
      spec.params[key] = item.substr(eq + 1);
      pos = comma + 1;
    }
  }
  spec.text = spec_text(spec);
  return spec;
}

std::string spec_text(const Spec& spec) {
  std::string text = spec.name;
  char sep = ':';
  for (const auto& [k, v] : spec.params) {
    text += sep + k + "=" + v;
    sep = ',';
  }
  return text;
}

bool same_spec(const Spec& a, const Spec& b) {
  if (a.name != b.name || a.params.size() != b.params.size()) return false;
  for (auto ia = a.params.begin(), ib = b.params.begin(); ia != a.params.end(); ++ia, ++ib) {
    if (ia->first != ib->first || !same_spec_value(ia->second, ib->second)) return false;
  }
  return true;
}

bool same_spec_value(const std::string& a, const std::string& b) {
  double x = 0.0, y = 0.0;
  return parse_double(a, x) && parse_double(b, y) ? x == y : a == b;
}

void reject_repeated_specs(const std::string& flag, const std::vector<Spec>& specs,
                           const std::vector<std::string>& texts) {
  reject_repeats(flag, specs, same_spec, [&](size_t i) { return i < texts.size() ? texts[i] : specs[i].text; });
}

std::vector<std::string> split_spec_list(const std::string& text) {
  std::vector<std::string> out;
  size_t pos = 0;
  while (pos <= text.size()) {
    const size_t comma = std::min(text.find(',', pos), text.size());
    const std::string token = text.substr(pos, comma - pos);
    const bool continues = token.find('=') != std::string::npos &&
                           token.find(':') == std::string::npos && !out.empty();
    if (continues)
      out.back() += "," + token;
    else
      out.push_back(token);  // empty too: parse_spec names it, instead of it being dropped
    pos = comma + 1;
  }
  return out;
}

std::vector<std::string> spec_list_items(const std::string& text, const std::string& flag) {
  if (text.empty()) throw InputError(flag, "is empty (expected specs separated by commas)");
  const std::vector<std::string> items = split_spec_list(text);
  const size_t n = items.size();
  for (size_t i = 0; i < n; ++i)
    if (items[i].empty())
      throw InputError(flag, "'" + text + "': item " + std::to_string(i + 1) + " of " +
                                 std::to_string(n) + " is empty (" +
                                 (i == 0       ? "a comma before the first spec"
                                  : i + 1 == n ? "a comma after the last spec"
                                               : "two commas in a row") +
                                 ")");
  return items;
}

SpecReader::SpecReader(const Spec& spec, std::string flag)
    : spec_(spec), flag_(std::move(flag)) {}

namespace {

// Looks up `key`, parses it with `parse` and checks [lo, hi]; `what` names the expected kind.
template <class T, class Parse>
T get_number(const Spec& spec, const std::string& flag, std::vector<std::string>& used,
             const std::string& key, T fallback, T lo, T hi, Parse parse, const char* what) {
  used.push_back(key);
  const auto it = spec.params.find(key);
  if (it == spec.params.end()) return fallback;
  T v{};
  if (!parse(it->second, v))
    throw InputError(flag, spec.name + ": '" + key + "' expects " + what + ", got '" + it->second + "'");
  if (v < lo || v > hi)
    throw InputError(flag, spec.name + ": '" + key + "' = " + it->second + " is outside [" +
                               number_text(double(lo)) + ", " + number_text(double(hi)) + "]");
  return v;
}

}  // namespace

double SpecReader::get_double(const std::string& key, double fallback, double lo, double hi) {
  return get_number<double>(spec_, flag_, used_, key, fallback, lo, hi,
                            [](const std::string& s, double& v) { return parse_double(s, v); },
                            "a number");
}

int SpecReader::get_int(const std::string& key, int fallback, int lo, int hi) {
  return int(get_number<long>(spec_, flag_, used_, key, fallback, lo, hi,
                              [](const std::string& s, long& v) { return parse_long(s, v); },
                              "an integer"));
}

bool SpecReader::get_bool(const std::string& key, bool fallback) {
  return get_int(key, fallback ? 1 : 0, 0, 1) != 0;
}

std::string SpecReader::get_choice(const std::string& key, const std::string& fallback,
                                   const std::vector<std::string>& choices) {
  used_.push_back(key);
  const auto it = spec_.params.find(key);
  if (it == spec_.params.end()) return fallback;
  if (std::find(choices.begin(), choices.end(), it->second) != choices.end()) return it->second;
  std::string known;
  for (const std::string& c : choices) known += (known.empty() ? "" : ", ") + c;
  throw InputError(flag_, spec_.name + ": '" + key + "' must be one of " + known + ", got '" +
                              it->second + "'");
}

std::string SpecReader::get_text(const std::string& key, const std::string& fallback) {
  used_.push_back(key);
  const auto it = spec_.params.find(key);
  if (it == spec_.params.end()) return fallback;
  return it->second;
}

bool SpecReader::has(const std::string& key) const { return spec_.params.count(key) > 0; }

bool SpecReader::gives(const std::string& key, const std::string& word) const {
  const auto it = spec_.params.find(key);
  return it != spec_.params.end() && it->second == word;
}

bool SpecReader::is_word(const std::string& key, const std::string& word) {
  used_.push_back(key);
  const auto it = spec_.params.find(key);
  return it != spec_.params.end() && it->second == word;
}

void SpecReader::reject_unknown() const {
  for (const auto& [k, v] : spec_.params)
    if (std::find(used_.begin(), used_.end(), k) == used_.end()) {
      std::string known;
      for (const std::string& u : used_) known += (known.empty() ? "" : ", ") + u;
      throw InputError(flag_, spec_.name + ": unknown parameter '" + k + "' (known: " + known + ")");
    }
}

}  // namespace shadowlab
