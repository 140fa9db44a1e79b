// Sources and doc pages say what holds and why, never when (and sources link docs pages, not
// README sections): no ordinal of a past work period
// ("the <ordinal> session"), no date (YYYY-MM-DD) and no issue number ("issue <N>"). Dates are
// provenance only on the results pages (docs/results/) and in docs/performance_history.md, which
// are not scanned. The scan walks the source tree's files by extension, not git, so it also sees
// files not yet committed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;

bool scanned_name(const fs::path& p) {
  static const std::set<std::string> exts = {".cpp", ".h", ".inl", ".c", ".sh", ".cmake", ".py",
                                             ".md", ".yaml", ".yml", ".txt"};
  const std::string name = p.filename().string();
  return exts.count(p.extension().string()) > 0 || name == "Snakefile" || name == "run";
}

// Relative paths (with '/') of every file the rule covers.
std::vector<std::string> covered_files(const fs::path& root) {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = fs::relative(it->path(), root).generic_string();
    if (it->is_directory()) {
      const std::string top = rel.substr(0, rel.find('/'));
      // Build trees, outputs and version control are not sources; the results and golden data
      // carry their provenance.
      if (top.rfind("build", 0) == 0 || top == ".git" || top == "out" || rel == "docs/results" ||
          rel == "tests/golden")
        it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || !scanned_name(it->path())) continue;
    if (rel == "docs/performance_history.md") continue;
    out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_word(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

int line_of(const std::string& text, size_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// Every finding in `text` (already lower case) as "LINE: what".
std::vector<std::string> findings(const std::string& text) {
  static const std::set<std::string> ordinals = {
      "first",     "second",     "third",      "fourth",     "fifth",      "sixth",   "seventh",
      "eighth",    "ninth",      "tenth",      "eleventh",   "twelfth",    "thirteenth",
      "fourteenth", "fifteenth", "sixteenth",  "seventeenth", "eighteenth", "nineteenth",
      "twentieth", "this",       "that",       "previous",   "same",       "next",    "last",
      "earlier",   "later"};
  std::vector<std::string> out;
  // An ordinal of a past work period: "<ordinal> session", across a comment's line break too.
  const std::string session = std::string("ses") + "sion";
  for (size_t p = text.find(session); p != std::string::npos; p = text.find(session, p + 1)) {
    if (p > 0 && is_word(text[p - 1])) continue;
    size_t e = p;
    while (e > 0 && (std::isspace(static_cast<unsigned char>(text[e - 1])) || text[e - 1] == '/' ||
                     text[e - 1] == '#' || text[e - 1] == '*'))
      --e;
    size_t b = e;
    while (b > 0 && is_word(text[b - 1])) --b;
    const std::string word = text.substr(b, e - b);
    if (ordinals.count(word)) out.push_back(std::to_string(line_of(text, p)) + ": \"" + word + " " + session + "\"");
  }
  // An issue number: the word, an optional s, blanks, an optional #, a digit.
  const std::string issue = std::string("iss") + "ue";
  for (size_t p = text.find(issue); p != std::string::npos; p = text.find(issue, p + 1)) {
    if (p > 0 && is_word(text[p - 1])) continue;
    size_t q = p + issue.size();
    if (q < text.size() && text[q] == 's') ++q;
    const size_t gap = q;
    while (q < text.size() && (text[q] == ' ' || text[q] == '\t')) ++q;
    if (q == gap) continue;
    if (q < text.size() && text[q] == '#') ++q;
    size_t end = q;
    while (end < text.size() && is_digit(text[end])) ++end;
    if (end > q) out.push_back(std::to_string(line_of(text, p)) + ": \"" + text.substr(p, end - p) + "\"");
  }
  // A date: four digits, '-', two digits, '-', two digits, not inside a longer number.
  for (size_t p = 0; p + 10 <= text.size(); ++p) {
    const char* s = text.data() + p;
    const bool shape = is_digit(s[0]) && is_digit(s[1]) && is_digit(s[2]) && is_digit(s[3]) && s[4] == '-' &&
                       is_digit(s[5]) && is_digit(s[6]) && s[7] == '-' && is_digit(s[8]) && is_digit(s[9]);
    if (!shape || (p > 0 && is_word(text[p - 1])) || (p + 10 < text.size() && is_word(text[p + 10]))) continue;
    out.push_back(std::to_string(line_of(text, p)) + ": date " + text.substr(p, 10));
  }
  return out;
}

TEST(SourceHygiene, FindingsRecognizeEachKind) {
  const auto f = [](const std::string& s) { return findings(lower(s)).size(); };
  EXPECT_EQ(f("// measured in the Eighteenth " + std::string("ses") + "sion."), 1u);
  EXPECT_EQ(f("// the twelfth\n// " + std::string("ses") + "sion's resolve"), 1u);
  EXPECT_EQ(f("// " + std::string("Iss") + "ue 11's rule"), 1u);
  EXPECT_EQ(f("// see " + std::string("iss") + "ues #4"), 1u);
  EXPECT_EQ(f("// Measured (" + std::string("2026") + "-11-28): 3 ms"), 1u);
  // Not findings: a user's session, an issue tracker named without a number, other numbers.
  EXPECT_EQ(f("// a user's " + std::string("ses") + "sion; an " + std::string("iss") + "ue of format"), 0u);
  EXPECT_EQ(f("x = 2026-11; y = 12026-11-288; a fifth of the time"), 0u);
}

TEST(SourceHygiene, NoOrdinalsDatesOrIssueNumbersOutsideResultsAndHistory) {
  const fs::path root = test::source_path("");
  const std::vector<std::string> files = covered_files(root);
  ASSERT_GT(files.size(), 100u) << "the scan found too few files under " << root;
  std::string report;
  for (const std::string& rel : files) {
    std::ifstream in(root / rel, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    for (const std::string& finding : findings(lower(ss.str()))) report += rel + ":" + finding + "\n";
  }
  EXPECT_TRUE(report.empty()) << "history belongs in docs/performance_history.md or docs/results/:\n"
                              << report;
}

// Code comments explain at the point of use or link a docs page: the README is a user's page
// whose sections move, so a source pointing into one ("README \"Techniques\"") goes stale.
TEST(SourceHygiene, SourcesPointToDocsPagesNotReadmeSections) {
  const fs::path root = test::source_path("");
  std::string report;
  for (const std::string& rel : covered_files(root)) {
    const std::string ext = fs::path(rel).extension().string();
    if (ext != ".cpp" && ext != ".h" && ext != ".inl") continue;
    std::ifstream in(root / rel, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const std::string pointer = std::string("READ") + "ME \"";
    for (size_t p = text.find(pointer); p != std::string::npos; p = text.find(pointer, p + 1))
      report += rel + ":" + std::to_string(line_of(text, p)) + "\n";
  }
  EXPECT_TRUE(report.empty()) << "comments that point into README sections:\n" << report;
}

}  // namespace
}  // namespace shadowlab
