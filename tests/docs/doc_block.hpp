#pragma once

// The fenced blocks of a Markdown document, as the docs test reads them (docs/testing.md, "Docs
// that run"): which are commands, how the test treats each (its `<!-- docs-test: ... -->`
// marker), and what a reader would type.
//
// A block's language is the first word after its opening fence. `sh`, `bash`, `shell` and
// `console` blocks are commands (in `console` only the lines starting with `$ ` and their
// continuations); every other language (`text`, `yaml`, `json`, ...) is not run. A block without
// a language is an error: the reader cannot tell a command from its output, and neither can the
// test.

#include <string>
#include <vector>

namespace fleetmap::docs {

// How the test treats a command block, from the marker on the line before its fence.
enum class BlockMode {
  kRun,          // no marker: the lines run as one script, which must exit 0
  kLongRunning,  // each command is a program of its own that runs until stopped
  kSynopsis,     // a command's shape: programs, subcommands and options checked against --help
  kSkip,         // not run; the marker says why
};

struct DocBlock {
  std::string file;  // the document, as reported (README.md, docs/view.md)
  int line = 0;      // the opening fence's line, from 1
  std::string language;
  BlockMode mode = BlockMode::kRun;
  std::string reason;               // the marker's text after the dash
  double hold_seconds = 3.0;        // kLongRunning: how long the programs must live
  std::vector<std::string> lines;   // between the fences, as written (indentation removed)
  std::vector<std::string> errors;  // what is wrong with the block or its marker

  bool IsCommands() const;
  // "docs/view.md:9": where the reader finds the block.
  std::string Where() const;
  // The doc's line number of the block's `index`th line (from 0).
  int LineOf(size_t index) const { return line + 1 + static_cast<int>(index); }
};

// Every fenced block of `text` (a Markdown document reported as `file`), in order. Errors that
// belong to no block (a marker before something other than a fence) come as a block of
// language "" with only `errors` set.
std::vector<DocBlock> ReadDocBlocks(const std::string& file, const std::string& text);

// What a reader would type, one entry per line of the block, so that a script's line N is the
// block's line N: `$ ` removed in console blocks, where output lines become empty.
std::vector<std::string> TypedLines(const DocBlock& block);

// One command a reader would type: a line and its backslash continuations, with the doc line it
// starts on. Empty lines and lines that are only a comment are not commands.
struct TypedCommand {
  int line = 0;
  std::string text;
};
std::vector<TypedCommand> TypedCommands(const DocBlock& block);

}  // namespace fleetmap::docs
