#pragma once

// `fleetmap learn-objects MAP1.yaml ... MAPT.yaml --out DIR [--json]`: learns the movable objects
// and their templates (classes) from maps of one place taken at different times
// (common/object_learning, docs/object-learning.md). Writes DIR/model.json (chosen N and M, the
// log posterior over the (N, M) grid searched, snapshot -> object and object -> template
// assignments with alignments), DIR/template_<m>.pgm, DIR/object_<n>.pgm and DIR/montage.png;
// --json prints model.json on stdout. Progress (stage, (N, M), EM iteration, elapsed, estimate)
// goes to stderr: redrawn in place on a terminal, a line every 10 s otherwise, none with --json.
// `--memory-budget MB` bounds the learner's memory (it degrades and warns past it).
//
// Exit codes: 0 (also when nothing moved: an empty model, said plainly), 2 for bad input (an
// unreadable map, fewer than two maps, maps whose size, resolution or origin differ: the message
// names the files), CLI11's for usage errors.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace fleetmap::cli {

struct LearnObjectsOptions {
  std::vector<std::string> maps;
  std::string out_dir;
  bool json = false;
  uint32_t seed = 1;
  int restarts = 0;                // 0: LearnOptions' default
  double object_penalty = -1.0;    // < 0: default
  double template_penalty = -1.0;  // < 0: default
  bool flat = false;               // the flat model (objects only)
  double memory_budget_mb = 0.0;   // <= 0: LearnOptions' default
  // Progress on `err`: -1 automatic (on unless --json), 0 never, 1 always.
  int progress = -1;
  bool err_is_terminal = false;  // redraw one line (else a line every 10 s)
};

int RunLearnObjects(const LearnObjectsOptions& options, std::ostream& out, std::ostream& err);

void AddLearnObjectsCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
