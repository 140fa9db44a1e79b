#pragma once
// Notes and warnings about inputs (which of a glTF file's lights is used, statements an OBJ
// reader skips, a --from file recorded by another build): held, not printed where they arise,
// so that an error found later while checking the inputs is still the only line on stderr.
// run_main (lab/cli.h) prints them after a successful run and drops them on an error.
#include <string>
#include <vector>

namespace shadowlab {

// Holds one line ("note: FILE: text"), printed later by print_notes.
void hold_note(const std::string& line);
// The held lines in order, emptying the store.
std::vector<std::string> take_notes();
// Prints the held lines to stderr, one per line, and empties the store.
void print_notes();

}  // namespace shadowlab
