#include "lab/param_space.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "core/spec.h"
#include "core/parse_number.h"
#include "techniques/registry/technique.h"
#include "lab/cli.h"

namespace shadowlab {
namespace {

// A computed value as text: whole numbers below 1e15 exactly, others to 4
// significant digits; an exponent is written without '+' ("1e18"; specs refuse '+').
std::string value_text(double v) {
  if (v == std::round(v) && std::fabs(v) < 1e15) return fmt::format("{:.0f}", v);
  std::string t = fmt::format("{:.4g}", v);
  if (const size_t e = t.find("e+"); e != std::string::npos) t.erase(e + 1, 1);
  // fmt pads the exponent to two digits: "1.235e04" is written "1.235e4".
  if (const size_t e = t.find("e0"); e != std::string::npos && e + 2 < t.size()) t.erase(e + 1, 1);
  return t;
}

// n as a whole number of steps, or -1 when it is not one (relative tolerance 1e-9: decimal
// steps such as 0.1 are not exact in binary).
long whole_steps(double n) {
  const double r = std::round(n);
  if (std::fabs(n - r) > 1e-9 * std::max(1.0, std::fabs(n))) return -1;
  return long(r);
}

}  // namespace

size_t ParamSpace::size() const {
  // Saturating: six keys of 4096 values each would wrap to 0 (2^72).
  size_t n = 1;
  for (const ParamDomain& d : keys) {
    const size_t k = d.values.size();
    if (k != 0 && n > SIZE_MAX / k) return SIZE_MAX;
    n *= k;
  }
  return n;
}

std::vector<std::string> parse_domain(const std::string& text, const std::string& flag) {
  auto fail = [&](const std::string& why) -> InputError {
    return InputError(flag, "'" + text + "': " + why);
  };
  auto number = [&](const std::string& s) {
    double v = 0.0;
    if (!parse_double(s, v)) throw fail("'" + s + "' is not a number");
    return v;
  };
  std::vector<std::string> values;
  const size_t dots = text.find("..");
  if (dots == std::string::npos) {
    for (const std::string& v : split(text, '|')) {
      if (v.empty()) throw fail("empty value in a list");
      if (values.size() >= kMaxDomainValues)
        throw fail("more than " + std::to_string(kMaxDomainValues) + " values");
      values.push_back(v);
    }
  } else {
    const size_t slash = text.find('/', dots);
    const std::string a_text = text.substr(0, dots);
    const std::string b_text = text.substr(dots + 2, slash == std::string::npos ? std::string::npos : slash - dots - 2);
    const double a = number(a_text), b = number(b_text);
    if (a > b) throw fail("empty range (" + a_text + " > " + b_text + ")");
    std::string step = slash == std::string::npos ? "" : text.substr(slash + 1);
    std::vector<double> v;
    auto check_count = [&](double n) {
      if (!(n < double(kMaxDomainValues))) throw fail("more than " + std::to_string(kMaxDomainValues) + " values");
    };
    if (step.empty()) {
      long ia = 0, ib = 0;
      if (slash != std::string::npos) throw fail("empty step after '/'");
      if (!parse_long(a_text, ia) || !parse_long(b_text, ib))
        throw fail("a range without a step needs whole-number ends (give /STEP)");
      check_count(double(ib) - double(ia));
      // Counted in unsigned arithmetic: `i <= ib` never ends for ib = LONG_MAX.
      const unsigned long count = (unsigned long)ib - (unsigned long)ia;
      for (unsigned long k = 0; k <= count; ++k) v.push_back(double(ia) + double(k));
    } else if (step[0] == 'x') {
      const double f = number(step.substr(1));
      if (!(f > 1.0)) throw fail("factor must be > 1");
      if (!(a > 0.0)) throw fail("a geometric range needs A > 0");
      const double n = std::log(b / a) / std::log(f);
      check_count(n);
      const long k = whole_steps(n);
      if (k < 0) throw fail("x" + step.substr(1) + " steps from " + a_text + " never reach " + b_text);
      for (long i = 0; i < k; ++i) v.push_back(a * std::pow(f, double(i)));
      v.push_back(b);
    } else if (step.rfind("lin", 0) == 0 || step.rfind("log", 0) == 0) {
      const bool log = step[1] == 'o';
      long n = 0;
      if (!parse_long(step.substr(3), n) || n < 2) throw fail("'" + step + "': need " + step.substr(0, 3) + "N with N >= 2");
      check_count(double(n));
      if (log && !(a > 0.0)) throw fail("a log range needs A > 0");
      for (long i = 0; i + 1 < n; ++i) {
        const double t = double(i) / double(n - 1);
        v.push_back(log ? a * std::pow(b / a, t) : a + (b - a) * t);
      }
      v.push_back(b);
    } else {
      const double s = number(step);
      if (!(s > 0.0)) throw fail("step must be > 0");
      const double n = (b - a) / s;
      check_count(n);
      const long k = whole_steps(n);
      if (k < 0) throw fail("steps of " + step + " from " + a_text + " never reach " + b_text);
      for (long i = 0; i < k; ++i) v.push_back(a + double(i) * s);
      v.push_back(b);
    }
    for (double x : v) values.push_back(value_text(x));
  }
  // Each value once as parsed ("3|03" is one value twice: core/spec.h same_spec_value), found
  // through ordered sets (a domain holds up to kMaxDomainValues values).
  std::map<double, size_t> numbers;
  std::map<std::string, size_t> texts;
  for (size_t i = 0; i < values.size(); ++i) {
    double x = 0.0;
    size_t first_index = i;
    if (parse_double(values[i], x))
      first_index = numbers.emplace(x, i).first->second;
    else
      first_index = texts.emplace(values[i], i).first->second;
    if (first_index == i) continue;
    const std::string& first = values[first_index];
    throw fail("value " + values[i] + (values[i] == first ? "" : " (the same as " + first + ")") + " occurs twice");
  }
  return values;
}

ParamSpace parse_param_space(const std::string& text, const std::string& flag) {
  ParamSpace s;
  s.text = text;
  const size_t colon = text.find(':');
  s.technique = text.substr(0, colon);
  if (s.technique.empty()) throw InputError(flag, "'" + text + "': no technique name");
  if (colon == std::string::npos) return s;
  for (const std::string& item : split(text.substr(colon + 1), ',')) {
    const size_t eq = item.find('=');
    if (item.empty() || eq == std::string::npos || eq == 0)
      throw InputError(flag, "'" + text + "': expected key=domain, got '" + item + "'");
    ParamDomain d;
    d.key = item.substr(0, eq);
    for (const ParamDomain& other : s.keys)
      if (other.key == d.key) throw InputError(flag, "'" + text + "': key " + d.key + " given twice");
    d.values = parse_domain(item.substr(eq + 1), flag + " '" + text + "' " + d.key);
    s.keys.push_back(std::move(d));
  }
  return s;
}

namespace {

// A domain's values as parsed: numbers as numbers, the rest as text (core/spec.h same_spec_value).
std::pair<std::set<double>, std::set<std::string>> parsed_values(const std::vector<std::string>& values) {
  std::pair<std::set<double>, std::set<std::string>> out;
  for (const std::string& v : values) {
    double x = 0.0;
    if (parse_double(v, x))
      out.first.insert(x);
    else
      out.second.insert(v);
  }
  return out;
}

}  // namespace

bool same_space(const ParamSpace& a, const ParamSpace& b) {
  if (a.technique != b.technique || a.keys.size() != b.keys.size()) return false;
  for (const ParamDomain& da : a.keys) {
    const ParamDomain* db = nullptr;
    for (const ParamDomain& d : b.keys)
      if (d.key == da.key) db = &d;
    if (!db || db->values.size() != da.values.size() || parsed_values(da.values) != parsed_values(db->values))
      return false;
  }
  return true;
}

std::vector<std::string> default_param_spaces() {
  // Depth compare on the three layouts that cover every direction, every filter on the cube,
  // and the neural technique on its shipped model.
  static const char* const kDefaultTuneTechniques[] = {"csm", "tsm", "dsm", "cvsm", "cesm",
                                                       "cevsm", "cmsm", "cpcss", "nsm"};
  std::vector<std::string> out;
  for (const char* name : kDefaultTuneTechniques) out.push_back(technique_tune_space(name, "--space"));
  return out;
}

std::string space_point(const ParamSpace& space, size_t i) {
  std::vector<std::string> parts(space.keys.size());
  for (size_t k = space.keys.size(); k-- > 0;) {
    const ParamDomain& d = space.keys[k];
    parts[k] = d.key + "=" + d.values[i % d.values.size()];
    i /= d.values.size();
  }
  std::string out = space.technique;
  for (size_t k = 0; k < parts.size(); ++k) out += (k == 0 ? ":" : ",") + parts[k];
  return out;
}

}  // namespace shadowlab
