#pragma once
// One declaration per key of a technique spec: its name, type, default, accepted range, help and
// the member it sets. Parsing and validation (read_keys), the "key=default,…" text of --help and
// --list-techniques (keys_text), the key tables of docs/techniques/keys.md (--list-keys) and
// tune's default spaces (lab/param_space.h) all read these declarations, so a key's
// facts live in one place. `P` is the parameter struct the keys fill (MapParams, RayTracedParams).
#include <string>
#include <vector>

#include "techniques/registry/technique_spec.h"

namespace shadowlab {

enum class KeyType {
  Integer,  // a whole number in [lo, hi]
  Number,   // a number in [lo, hi]; `word` may name one more accepted value
  Flag,     // 0 or 1
  Choice,   // one of `choices`
  Text,     // any non-empty text without ',' or ':' (a file path); `choices` describes it
};

// What a spec gave for a key, as its declaration's type reads it.
struct KeyValue {
  double number = 0.0;  // Integer, Number, Flag; a Number given as its word: the declared default
  std::string word;     // Choice, Text: the word; Number: `word` when the spec gives it
  bool given = false;   // the spec names the key
};

// What a key's check sees right after the key is read.
struct KeyCheck {
  SpecReader& reader;
  const std::string& name;  // the technique's name, first word of every message
  const char* flag;         // where the spec came from
  const KeyValue& value;
};

template <class P>
struct KeyDecl {
  const char* name = "";
  KeyType type = KeyType::Number;
  double def = 0.0;            // Integer, Number (unless def_word), Flag
  const char* def_word = "";   // Choice and Text default; Number: the default when it is `word`
  double lo = 0.0, hi = 0.0;   // accepted range (Integer, Number)
  // The reader refuses values outside [lo, parse_hi] ("is outside"); values in (hi, parse_hi]
  // are left to `check`, which refuses them with the reason (0: parse_hi = hi).
  double parse_hi = 0.0;
  const char* choices = "";    // Choice: the accepted words, "a|b|c"; Text: what it names
  const char* word = "";       // Number: one more accepted value, e.g. "light"
  const char* help = "";
  const char* needs = "";      // "key=word": read only when the spec gives key=word ("": always)
  const char* tune = "";       // tune's default domain (lab/param_space.h; "": not searched)
  void (*store)(P&, const KeyValue&) = nullptr;  // sets the member(s) the key names
  void (*check)(const KeyCheck&, P&) = nullptr;  // rules beyond the range, after `store`
};

// The type-free part of a declaration, for texts and tables.
struct KeyInfo {
  std::string name, def, range, help, needs, tune;
  bool text = false;  // KeyType::Text: `range` describes the value, it lists none
};

// Reads one key of r's spec (nothing when its `needs` is not met) into the value it parses.
bool read_key_value(SpecReader& r, const char* name, KeyType type, double def, const char* def_word,
                    double lo, double hi, const char* choices,
                    const char* word, const char* needs, KeyValue& v);
// The default as --help shows it ("512", "1e-06", "cross", "light").
std::string key_default_text(KeyType type, double def, const char* def_word);
// The accepted values as docs show them ("1..4096", "[0, 1000]", "0|1", "grid|poisson").
std::string key_range_text(KeyType type, double lo, double hi, const char* choices,
                           const char* word);

template <class P>
KeyInfo key_info(const KeyDecl<P>& k) {
  return {k.name, key_default_text(k.type, k.def, k.def_word),
          key_range_text(k.type, k.lo, k.hi, k.choices, k.word), k.help, k.needs, k.tune,
          k.type == KeyType::Text};
}

template <class P>
std::vector<KeyInfo> key_infos(const std::vector<KeyDecl<P>>& keys) {
  std::vector<KeyInfo> out;
  for (const KeyDecl<P>& k : keys) out.push_back(key_info(k));
  return out;
}

// Every declared default into p.
template <class P>
void store_defaults(const std::vector<KeyDecl<P>>& keys, P& p) {
  for (const KeyDecl<P>& k : keys) {
    KeyValue v;
    v.number = k.def;
    v.word = k.def_word;
    k.store(p, v);
  }
}

// Reads the declared keys in order into p, each checked as it is read (InputError naming flag
// and the key); the caller's SpecReader::reject_unknown then refuses any key not declared.
template <class P>
void read_keys(SpecReader& r, const std::string& name, const char* flag,
               const std::vector<KeyDecl<P>>& keys, P& p) {
  for (const KeyDecl<P>& k : keys) {
    KeyValue v;
    if (!read_key_value(r, k.name, k.type, k.def, k.def_word, k.lo,
                        k.parse_hi > 0.0 ? k.parse_hi : k.hi, k.choices, k.word, k.needs, v))
      continue;
    k.store(p, v);
    if (k.check) k.check(KeyCheck{r, name, flag, v}, p);
  }
}

// "key=default,…" in declaration order.
std::string keys_text(const std::vector<KeyInfo>& keys);

}  // namespace shadowlab
