#pragma once
/// \file The papers `formsim reproduce` knows, as data: for each, its cases (a shipped scenario
/// with overrides), its tables (rows of cases, columns of metrics and how to show them over the
/// seeds) and its bar charts. The README's reproduction tables are what these print.

#include <string>
#include <vector>

#include "sim/core/reproduction.hpp"

namespace formsim::app {

/// formation, agv, inspection, velocity (each checked with sim::CheckPaper).
const std::vector<sim::ReproPaper>& ReproPapers();

/// The paper called `name`. Throws std::runtime_error listing the papers.
const sim::ReproPaper& FindReproPaper(const std::string& name);

}  // namespace formsim::app
