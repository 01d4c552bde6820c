#pragma once
/// \file The papers `formsim reproduce` knows. Each kind declares its paper beside itself
/// (sim/<kind>/<kind>_paper.cpp, linked whole like the kind) and registers it:
///
///   ReproPaper AgvPaper() { ... }
///   FORMSIM_REGISTER_PAPER(AgvPaper);

#include <string>
#include <vector>

#include "sim/study/reproduction.hpp"

namespace formsim::sim {

/// Registers a paper's definition (built once, on first use). Returns true.
bool RegisterReproPaper(ReproPaper (*make)());

/// Every registered paper, each checked with CheckPaper, in the order of their numbers.
const std::vector<ReproPaper>& ReproPapers();

/// The paper called `name`. Throws std::runtime_error listing the papers.
const ReproPaper& FindReproPaper(const std::string& name);

}  // namespace formsim::sim

#define FORMSIM_PAPER_CAT2(a, b) a##b
#define FORMSIM_PAPER_CAT(a, b) FORMSIM_PAPER_CAT2(a, b)
/// Registers `make` (a function returning the ReproPaper) with `formsim reproduce`.
#define FORMSIM_REGISTER_PAPER(make)                                                  \
  [[maybe_unused]] static const bool FORMSIM_PAPER_CAT(kPaperRegistered_, __LINE__) = \
      ::formsim::sim::RegisterReproPaper(&make)
