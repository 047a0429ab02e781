// The physics validation suite: each case compares the engine with a reference (analytic
// solution, conservation law, published result) at several fidelities, so that speed can
// be read against error. `fibrenet validate` and the GoogleTest suite run the same cases.
#pragma once

#include <string>
#include <vector>

namespace fibrenet::validation {

struct CaseResult {
  std::string name;      // case name, the same for every fidelity of a case
  std::string fidelity;  // e.g. "n=21 dt=0.5dtc"; the default fidelity is marked "(default)"
  bool is_default = false;
  double error = 0.0;      // relative error against the reference (or as the case states)
  double tolerance = 0.0;  // pass threshold for this fidelity
  bool passed = false;
  double wall_s = 0.0;     // wall time of this fidelity's run [s]
  std::string detail;      // measured vs reference, in words
};

using CaseRunner = std::vector<CaseResult> (*)();

struct CaseEntry {
  const char* name;
  const char* description;  // what is held against what
  CaseRunner run;
};

// All cases, one row each (registry.cpp).
const std::vector<CaseEntry>& Cases();

// Fills passed from error and tolerance and returns the result (a small convenience so
// that every case decides pass/fail the same way).
CaseResult Finish(CaseResult r);

}  // namespace fibrenet::validation
