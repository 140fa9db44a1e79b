#include "scenes/obj_text_check.h"

#include <array>
#include <cfloat>
#include <climits>
#include <cstdint>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"

namespace shadowlab {
namespace {

[[noreturn]] void fail(const std::string& path, size_t line, const std::string& what);

// tinyobjloader's rules, which the check must share or the two read different geometry from the
// same bytes: a token ends at a space or a tab only (IS_SPACE), and a line at "\n", "\r\n" or a
// lone "\r" (safeGetline). Other control bytes (\v, \f, NUL, …) are rejected before parsing.
bool is_space(char c) { return c == ' ' || c == '\t'; }

// The line starting at `pos`: [pos, end) without its terminator; `next` is where the following
// line starts.
std::string_view next_line(std::string_view text, size_t pos, size_t& next) {
  size_t eol = text.find_first_of("\r\n", pos);
  if (eol == std::string_view::npos) eol = text.size();
  next = eol + 1;
  if (eol < text.size() && text[eol] == '\r' && eol + 1 < text.size() && text[eol + 1] == '\n')
    next = eol + 2;
  return text.substr(pos, eol - pos);
}

// Rejects bytes that tinyobjloader and this check would not read alike, and UTF-16 text.
void check_bytes(const std::string& path, std::string_view text) {
  const bool bom16 = text.size() >= 2 && ((uint8_t(text[0]) == 0xFF && uint8_t(text[1]) == 0xFE) ||
                                          (uint8_t(text[0]) == 0xFE && uint8_t(text[1]) == 0xFF));
  const bool zero_high = text.size() >= 4 && text[1] == '\0' && text[3] == '\0' && text[0] != '\0';
  if (bom16 || zero_high)
    throw InputError(path, "is UTF-16 text; save it as UTF-8 (or ASCII)");
  size_t line = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n' || (c == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n'))) {
      ++line;
      continue;
    }
    if (c < 0x20 && c != '\t' && c != '\r')
      fail(path, line, "control byte 0x" + std::string(1, "0123456789ABCDEF"[c >> 4]) +
                           std::string(1, "0123456789ABCDEF"[c & 15]) +
                           " (only tabs and line ends are allowed)");
  }
}

// The whitespace-separated tokens of a line (storage reused from line to line).
struct Tokens {
  std::vector<std::string_view> tok;
  size_t count() const { return tok.size(); }
};

void tokenize(std::string_view line, Tokens& out) {
  out.tok.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i >= line.size()) break;
    const size_t b = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    out.tok.push_back(line.substr(b, i - b));
  }
}

// Printable, shortened copy of a token for error messages (garbage files hold binary bytes).
std::string printable(std::string_view s) {
  std::string r;
  for (char c : s.substr(0, 24)) r += (c >= 32 && c < 127) ? c : '?';
  if (s.size() > 24) r += "...";
  return r;
}

// 'key' in single quotes (built by appending: GCC 12 warns falsely on "'" + std::string).
std::string quoted(std::string_view key) {
  std::string r(1, '\'');
  r.append(key);
  r += '\'';
  return r;
}

enum class Num { kOk, kNotNumber, kNonFinite };

// Parses a whole token as a decimal number (a leading '+' is allowed). Values beyond the
// float range count as non-finite: tinyobjloader stores floats.
Num parse_number(std::string_view s, double& value) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, value, std::chars_format::general);
  if (r.ptr != end || s.empty()) return Num::kNotNumber;
  if (r.ec == std::errc::result_out_of_range) {
    // Underflow to a denormal/zero is harmless; overflow is infinite.
    const size_t e = s.find_first_of("eE");
    const bool tiny = e != std::string_view::npos && e + 1 < s.size() && s[e + 1] == '-';
    if (tiny) {
      value = 0.0;
      return Num::kOk;
    }
    return Num::kNonFinite;
  }
  if (r.ec != std::errc()) return Num::kNotNumber;
  if (!std::isfinite(value) || std::fabs(value) > double(FLT_MAX)) return Num::kNonFinite;
  return Num::kOk;
}

bool parse_int(std::string_view s, long long& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, v);
  return !s.empty() && r.ptr == end && r.ec == std::errc();
}

[[noreturn]] void fail(const std::string& path, size_t line, const std::string& what) {
  throw InputError(path, "line " + std::to_string(line) + ": " + what);
}

// Statements that are valid OBJ but carry nothing shadowlab uses.
bool is_ignored_statement(std::string_view k) {
  static constexpr std::string_view kIgnored[] = {
      "vp",     "cstype",     "deg",       "bmat",     "step",     "curv", "curv2",
      "surf",   "parm",       "trim",      "hole",     "scrv",     "sp",   "end",
      "con",    "mg",         "bevel",     "c_interp", "d_interp", "lod",  "maplib",
      "usemap", "shadow_obj", "trace_obj", "ctech",    "stech",    "l",    "p"};
  for (std::string_view s : kIgnored)
    if (k == s) return true;
  return false;
}

// Checks one face corner "v", "v/vt", "v//vn" or "v/vt/vn". Indices are 1-based or negative
// (relative to the count so far); positive ones are range-checked at the end of the file.
void check_corner(const std::string& path, size_t line, std::string_view c, const ObjTextSummary& s,
                  std::array<long long, 3>& max_index, std::array<size_t, 3>& max_line) {
  std::array<std::string_view, 3> part{};
  size_t n = 0, b = 0;
  for (size_t i = 0; i <= c.size(); ++i)
    if (i == c.size() || c[i] == '/') {
      if (n == 3) fail(path, line, "face corner '" + printable(c) + "' has more than 3 parts");
      part[n++] = c.substr(b, i - b);
      b = i + 1;
    }
  const size_t counts[3] = {s.positions, s.texcoords, s.normals};
  const char* what[3] = {"vertex", "texcoord", "normal"};
  for (size_t k = 0; k < n; ++k) {
    if (part[k].empty()) {
      if (k == 1 && n == 3) continue;  // "v//vn": no texcoord
      fail(path, line, "face corner '" + printable(c) + "' has an empty index");
    }
    long long idx = 0;
    if (!parse_int(part[k], idx))
      fail(path, line, "face corner '" + printable(c) + "' is not an index");
    // tinyobjloader keeps indices in an int: beyond its range no file can be right (and
    // negating the most negative long long below would overflow).
    if (idx > INT_MAX || idx < -INT_MAX)
      fail(path, line, "face corner '" + printable(c) + "' has an index out of range");
    if (idx == 0) fail(path, line, "face corner '" + printable(c) + "' uses index 0");
    if (idx < 0 && size_t(-idx) > counts[k])
      fail(path, line,
           std::string("face refers to ") + what[k] + " " + std::to_string(idx) + " but only " +
               std::to_string(counts[k]) + " precede it");
    if (idx > max_index[k]) {
      max_index[k] = idx;
      max_line[k] = line;  // the first face that uses the largest index
    }
  }
}

}  // namespace

ObjTextSummary check_obj_text(const std::string& path, std::string_view text) {
  ObjTextSummary s;
  Tokens t;
  std::array<long long, 3> max_index{0, 0, 0};  // largest positive v, vt, vn index used
  std::array<size_t, 3> max_line{0, 0, 0};      // the line of its first use
  size_t ignored = 0, line_no = 0;
  std::string first_ignored;
  size_t pos = 0;
  check_bytes(path, text);
  while (pos < text.size()) {
    size_t next = 0;
    const std::string_view line = next_line(text, pos, next);
    pos = next;
    ++line_no;
    tokenize(line, t);
    if (t.count() == 0 || t.tok[0][0] == '#') continue;
    const std::string_view key = t.tok[0];
    const size_t args = t.count() - 1;
    if (key == "v" || key == "vn" || key == "vt") {
      const bool is_v = key == "v", is_vn = key == "vn";
      const size_t lo = is_v ? 3 : is_vn ? 3 : 1, hi = is_v ? 7 : 3;
      if (args < lo || args > hi)
        fail(path, line_no,
             quoted(key) + " needs " + std::to_string(lo) +
                 (lo == hi ? "" : ".." + std::to_string(hi)) + " numbers, got " +
                 std::to_string(args));
      const size_t index = (is_v ? s.positions : is_vn ? s.normals : s.texcoords) + 1;
      for (size_t i = 1; i < t.count(); ++i) {
        double value = 0.0;
        const Num r = parse_number(t.tok[i], value);
        if (r == Num::kNotNumber)
          fail(path, line_no,
               quoted(key) + " has a non-numeric value '" + printable(t.tok[i]) + "'");
        if (r == Num::kNonFinite)
          throw InputError(path, std::string(is_v    ? "vertex "
                                             : is_vn ? "normal "
                                                     : "texcoord ") +
                                     std::to_string(index) + " (line " + std::to_string(line_no) +
                                     ") has a NaN or infinite (or float-overflowing) coordinate");
      }
      (is_v ? s.positions : is_vn ? s.normals : s.texcoords) += 1;
    } else if (key == "f") {
      if (args < 3)
        fail(path, line_no, "face with " + std::to_string(args) + " corners (needs 3+)");
      for (size_t i = 1; i < t.count(); ++i) check_corner(path, line_no, t.tok[i], s, max_index, max_line);
      ++s.faces;
      s.triangles += args - 2;
    } else if (key == "g" || key == "o" || key == "s") {
      // group / object / smoothing group: names are free-form
    } else if (key == "usemtl" || key == "mtllib") {
      if (args < 1) fail(path, line_no, quoted(key) + " without a name");
      if (key == "mtllib") s.has_mtllib = true;
    } else if (is_ignored_statement(key)) {
      if (ignored++ == 0) first_ignored = std::string(key);
    } else {
      fail(path, line_no, "unknown statement '" + printable(key) + "'");
    }
  }
  const size_t counts[3] = {s.positions, s.texcoords, s.normals};
  const char* what[3] = {"vertex", "texcoord", "normal"};
  for (int k = 0; k < 3; ++k)
    if (max_index[size_t(k)] > (long long)counts[k])
      fail(path, max_line[size_t(k)],
           std::string("face refers to ") + what[k] + " " + std::to_string(max_index[size_t(k)]) +
               " but the file has " + std::to_string(counts[k]));
  if (ignored > 0)
    s.notes.push_back(std::to_string(ignored) +
                      " statement(s) without triangles ignored (first: '" + first_ignored + "')");
  return s;
}

void check_mtl_text(const std::string& path, std::string_view text) {
  Tokens t;
  size_t line_no = 0, pos = 0;
  check_bytes(path, text);
  while (pos < text.size()) {
    size_t next = 0;
    const std::string_view line = next_line(text, pos, next);
    pos = next;
    ++line_no;
    tokenize(line, t);
    if (t.count() == 0 || t.tok[0][0] == '#') continue;
    const std::string_view key = t.tok[0];
    if (key == "newmtl") {
      if (t.count() < 2) fail(path, line_no, "'newmtl' without a name");
    } else if (key == "Kd" || key == "d" || key == "Tr") {
      size_t first = 1;
      if (key == "d" && t.count() > 1 && t.tok[1] == "-halo") first = 2;
      if (t.count() <= first) fail(path, line_no, quoted(key) + " without a value");
      // Kd may also be "Kd spectral file" or "Kd xyz x y z": only plain numbers are checked.
      if (key == "Kd" && (t.tok[1] == "spectral" || t.tok[1] == "xyz")) continue;
      for (size_t i = first; i < t.count(); ++i) {
        double v = 0.0;
        if (parse_number(t.tok[i], v) != Num::kOk)
          fail(path, line_no, quoted(key) + " has an invalid value '" + printable(t.tok[i]) + "'");
      }
    }
  }
}

}  // namespace shadowlab
