#pragma once
/// \file What an export asks of a scenario's figures, checked before anything runs: every
/// figure text is good label markup, and every figure named by `--log-y` exists (the error
/// lists the figures there are).

#include <set>
#include <string>
#include <vector>

#include "sim/core/figure_spec.hpp"
#include "sim/core/provenance.hpp"

namespace formsim::app {

/// Parses "NAME,NAME,..." (spaces around names ignored). Throws std::runtime_error naming
/// `flag` for an empty list or an empty name.
std::set<std::string> ParseFigureNames(const std::string& list, const std::string& flag);

/// The figures of the scenario `file` with `overrides` as a run makes them, from a throwaway
/// session stepped once (some figures appear with the first recorded row).
std::vector<sim::FigureSpec> ProbeFigures(const std::string& file,
                                          const std::vector<sim::Override>& overrides);

/// Throws std::runtime_error when a figure's text has bad markup ("figure 'phi_error' series
/// 2: unknown markup command ...") or a name of `log_y` (given by `flag`) is not a time plot
/// of `figures` (listing them).
void CheckFigureRequests(const std::vector<sim::FigureSpec>& figures,
                         const std::set<std::string>& log_y, const std::string& flag = "--log-y");

}  // namespace formsim::app
