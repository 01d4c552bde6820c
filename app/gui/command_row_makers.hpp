#pragma once
/// \file Makers of command-table arguments (app/gui/command_table.hpp), shared by the panels
/// that register rows: each row's argument list reads as a list of these calls.

#include <functional>
#include <string>
#include <vector>

#include "app/gui/command_table.hpp"

namespace formsim::app::rows {

/// A whole number in [lo, hi].
CommandArg Whole(std::string name, double lo, double hi, std::string unit = "");
/// A finite number in [lo, hi].
CommandArg Real(std::string name, double lo, double hi, std::string unit = "");
/// Free text (`type` kRest: the rest of the line; kWord: one word; kChoice: the window's).
CommandArg Text(std::string name, std::string what, ArgType type = ArgType::kRest);
/// on|off|toggle.
CommandArg OnOff();
/// One of `choices`.
CommandArg Choice(std::string name, std::vector<std::string> choices);
/// `a`, which may be left out.
CommandArg Optional(CommandArg a);
/// `a` with the window's suggestions (or choices, for kChoice).
CommandArg Offer(CommandArg a, std::function<std::vector<std::string>(const AppUi&)> offer);
/// `a` with the value the menu's argument dialog starts from.
CommandArg Initial(CommandArg a, std::function<std::string(const AppUi&)> initial);

/// "nobody", then every robot of the live run (follow, slot).
std::vector<std::string> RobotNames(const AppUi& ui);

}  // namespace formsim::app::rows
