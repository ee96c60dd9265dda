#pragma once

// Checks a synopsis block (docs/testing.md, "Docs that run"): the shape of commands, with
// placeholders (`DIR`, `...`) and optional parts (`[--seed S]`), which cannot run as written but
// must not drift from the programs either. Each entry names a program; the words after it that
// are its subcommands, and every option it shows, must be in the program's `--help`.
//
// An entry is a line with the lines indented under it (or joined by a backslash); `;` separates
// entries on one line, `#` starts a comment, `a|b` (or `a | b`) are subcommands that each take the
// options that follow. In a console block only the commands (`$ ` lines) are entries.

#include <map>
#include <string>
#include <vector>

#include "tests/docs/doc_block.hpp"

namespace fleetmap::docs {

// What a program's --help lists: its options (`--name`, `-n`) and subcommands.
struct HelpText {
  std::vector<std::string> options;
  std::vector<std::string> subcommands;
};

// Reads CLI11's help: option lines start with the option's names (`-o,--out TEXT ...`), and the
// lines of a "Subcommands:" section with a subcommand's name.
HelpText ParseHelp(const std::string& help);

// `programs` maps a program's name, as the docs write it, to the executable to ask. Returns the
// failures, each "FILE:LINE: what"; empty when the block agrees with the programs.
std::vector<std::string> CheckSynopsis(const DocBlock& block,
                                       const std::map<std::string, std::string>& programs);

}  // namespace fleetmap::docs
