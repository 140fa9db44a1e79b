#include "techniques/registry/technique_keys.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/parse_number.h"

namespace shadowlab {
namespace {

std::vector<std::string> choice_words(const std::string& choices) {
  std::vector<std::string> out;
  for (size_t at = 0; at <= choices.size();) {
    const size_t bar = std::min(choices.find('|', at), choices.size());
    out.push_back(choices.substr(at, bar - at));
    at = bar + 1;
  }
  return out;
}

}  // namespace

bool read_key_value(SpecReader& r, const char* name, KeyType type, double def, const char* def_word,
                    double lo, double hi, const char* choices,
                    const char* word, const char* needs, KeyValue& v) {
  if (*needs) {
    const std::string n = needs;
    const size_t eq = n.find('=');
    if (!r.gives(n.substr(0, eq), n.substr(eq + 1))) return false;
  }
  v.given = r.has(name);
  switch (type) {
    case KeyType::Integer:
      v.number = r.get_int(name, int(def), int(lo), int(hi));
      break;
    case KeyType::Flag:
      v.number = r.get_bool(name, def != 0.0) ? 1.0 : 0.0;
      break;
    case KeyType::Choice:
      v.word = r.get_choice(name, def_word, choice_words(choices));
      break;
    case KeyType::Text:
      v.word = r.get_text(name, def_word);
      break;
    case KeyType::Number:
      if (*word && r.is_word(name, word)) {
        v.word = word;
        v.number = def;
      } else {
        v.number = r.get_double(name, def, lo, hi);
      }
      break;
  }
  return true;
}

std::string key_default_text(KeyType type, double def, const char* def_word) {
  if (type == KeyType::Choice || type == KeyType::Text || *def_word) return def_word;
  return fmt::format("{:g}", def);
}

std::string key_range_text(KeyType type, double lo, double hi, const char* choices,
                           const char* word) {
  switch (type) {
    case KeyType::Integer:
      return number_text(lo) + ".." + number_text(hi);
    case KeyType::Flag:
      return "0|1";
    case KeyType::Choice:
    case KeyType::Text:
      return choices;
    case KeyType::Number:
      return "[" + number_text(lo) + ", " + number_text(hi) + "]" + (*word ? std::string(" or ") + word : "");
  }
  return "";
}

std::string keys_text(const std::vector<KeyInfo>& keys) {
  std::string s;
  for (const KeyInfo& k : keys) s += (s.empty() ? "" : ",") + k.name + "=" + k.def;
  return s;
}

}  // namespace shadowlab
