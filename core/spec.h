#pragma once
// Specs "name:key=value,key=value" — techniques ("csm:res=1024,pcf=3") and slides
// ("grid:amp=1,freq=4") alike. Parsing is strict: empty items, a trailing comma, repeated keys,
// unknown keys (SpecReader::reject_unknown) and malformed values (no spaces, no '+', no hex:
// core/parse_number.h) are InputErrors naming the flag, so a typo never silently runs a default.
#include <map>
#include <string>
#include <vector>

namespace shadowlab {

struct Spec {
  std::string name;                           // e.g. "csm", "grid"
  std::map<std::string, std::string> params;  // key → raw value
  std::string text;                           // canonical text "name:k=v,..." (keys sorted)
};

// Parses one spec. `flag` names where it came from (for error messages, e.g. "--technique").
Spec parse_spec(const std::string& text, const std::string& flag);
// Canonical text of a spec: "name:k=v,..." with keys in sorted order ("name" alone without params).
std::string spec_text(const Spec& spec);
// True when a and b name the same thing: the same name and keys, each value equal as parsed
// (numbers as numbers: "pcf=3" and "pcf=03", "bias=0.01" and "bias=1e-2"; other values as text).
// Keys a spec leaves at their defaults are not filled in: "csm" and "csm:pcf=1" differ.
bool same_spec(const Spec& a, const Spec& b);
// One value of a spec as parsed: numbers as numbers ("3" and "03"), anything else as text.
bool same_spec_value(const std::string& a, const std::string& b);
// reject_repeats (core/repeats.h) over parsed specs by same_spec, naming them as written.
void reject_repeated_specs(const std::string& flag, const std::vector<Spec>& specs,
                           const std::vector<std::string>& texts);
// Splits a comma-separated list of specs, where a spec's own parameters also use commas:
// a token with '=' but no ':' continues the previous spec. "csm:res=64,pcf=3,rt" →
// {"csm:res=64,pcf=3", "rt"}. Empty items are kept ("csm,,rt" → {"csm", "", "rt"}) so that
// parse_spec rejects them.
std::vector<std::string> split_spec_list(const std::string& text);
// split_spec_list for a flag's list: an empty list or an empty item is an InputError naming the
// item by its position and the comma that made it ("'csm,': item 2 of 2 is empty (a comma
// after the last spec)").
std::vector<std::string> spec_list_items(const std::string& text, const std::string& flag);

// Typed accessors over a spec's params, each checking the range and naming the spec in errors.
// The key is marked as used; reject_unknown() throws for any param no accessor asked for.
class SpecReader {
 public:
  SpecReader(const Spec& spec, std::string flag);
  int get_int(const std::string& key, int fallback, int lo, int hi);
  double get_double(const std::string& key, double fallback, double lo, double hi);
  bool get_bool(const std::string& key, bool fallback);
  // One of `choices` (exact text), else InputError listing them.
  std::string get_choice(const std::string& key, const std::string& fallback,
                         const std::vector<std::string>& choices);
  // The value as written (a file path), or fallback (parse_spec refuses an empty value).
  std::string get_text(const std::string& key, const std::string& fallback);
  // True when the spec gives `key` (whatever its value; does not mark it used).
  bool has(const std::string& key) const;
  // True when `key` is given as exactly `word`, without marking it used.
  bool gives(const std::string& key, const std::string& word) const;
  // True when `key` is given as exactly `word` (e.g. "light_size=light"); marks it used.
  bool is_word(const std::string& key, const std::string& word);
  void reject_unknown() const;

 private:
  const Spec& spec_;
  std::string flag_;
  std::vector<std::string> used_;
};

}  // namespace shadowlab
