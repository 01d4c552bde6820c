#pragma once
/// \file The window's commands as one table (after MuJoCo simulate's `mjuiDef` rows): each row
/// names a command once and gives its arguments (types, ranges, units), its keys, its menu path,
/// a line of help, when it is enabled and its handler. Everything else is generated from the
/// table: the `--script` dispatch and its refusals, the keyboard, the menu bar, the command
/// palette, the F1 help, `formsim gui --help`, `formsim gui --list-commands` and the README's
/// table of script actions (tests/app/command_table_test.cpp checks each of them).

#include <functional>
#include <string>
#include <vector>

namespace formsim::app {

class AppUi;

/// What an argument accepts.
enum class ArgType {
  kWord,    ///< one word (a name, a mode)
  kRest,    ///< the rest of the line, spaces included (a path, a key=value, a sub-command)
  kWhole,   ///< a whole number in [lo, hi]
  kReal,    ///< a finite number in [lo, hi]
  kOnOff,   ///< on|off|toggle (also true|false|1|0)
  kChoice,  ///< one of `choices` (or of the choices the window offers now)
};

/// One argument of a command.
struct CommandArg {
  std::string name;  ///< as the help shows it: "PATH", "N", "T"
  ArgType type = ArgType::kWord;
  double lo = 0, hi = 0;             ///< kWhole, kReal: the accepted range, inclusive
  std::string unit;                  ///< "s", "m", "" for none
  std::vector<std::string> choices;  ///< kChoice: fixed choices
  /// kChoice with choices that depend on the window (robots, shipped scenarios, pins), and the
  /// menu's and palette's suggestions for a kWord or kRest argument.
  std::function<std::vector<std::string>(const AppUi&)> offer;
  /// The text the menu's argument dialog starts from (the window's current value).
  std::function<std::string(const AppUi&)> initial;
  /// The heading a value is listed under in the menu's submenu (the offer lists each group's
  /// values together): the lessons by paper. Null: no headings.
  std::function<std::string(const std::string&)> group;
  std::string what;       ///< what a kWord / kRest / window-chosen argument is: "a robot's name"
  bool optional = false;  ///< may be left out (only the last arguments)
  /// One line on what the argument is, for the help and the dialog.
  std::string TypeText() const;
};

/// The arguments of one call, parsed and checked against the row.
struct CommandArgs {
  std::vector<std::string> text;  ///< each argument as given (after toggle: "on" / "off")
  std::vector<double> number;     ///< kWhole, kReal: the value; kOnOff: 1 / 0
  bool Has(std::size_t i) const { return i < text.size(); }
  const std::string& Text(std::size_t i) const { return text.at(i); }
  double Real(std::size_t i) const { return number.at(i); }
  long long Whole(std::size_t i) const { return static_cast<long long>(number.at(i)); }
  bool On(std::size_t i) const { return number.at(i) != 0; }
};

/// Where a command came from: some act differently when a person is there (a save asks before
/// overwriting; a script's save overwrites).
enum class CommandSource { kScript, kKey, kMenu, kPalette, kButton };

/// One row of the table.
struct Command {
  std::string name;  ///< the script action, the palette's and --list-commands' name
  std::vector<CommandArg> args;
  /// Keys that run it: "space", ".", "r", "?", "F1", "Esc", "Ctrl+Z", "Ctrl+Shift+Z", "Ctrl+K".
  std::vector<std::string> keys;
  std::string key_args;  ///< the arguments a key passes ("toggle" for on|off commands)
  std::string menu;      ///< "View/Presentation mode"; "" for script-only commands
  std::string help;      ///< one line
  /// "" when the command can run now, else why not (the menu greys it out with this tooltip;
  /// a script gets it as the refusal).
  std::function<std::string(const AppUi&)> disabled;
  /// For on|off commands: the state now (the menu's check mark, and what toggle flips).
  std::function<bool(const AppUi&)> checked;
  /// Runs it: "" or why it was refused.
  std::function<std::string(AppUi&, const CommandArgs&, CommandSource)> run;
  bool script_only = false;   ///< meaningful only in a script (wait); no menu entry
  bool ends_program = false;  ///< quits the window (left out of the chaos test)
  /// The usage line: "seeds N", "screenshot [PATH]".
  std::string Usage() const;
  /// The keys as the help shows them: "space", "Ctrl+Z, Ctrl+Shift+Z".
  std::string KeysText() const;
};

/// Every command of the window, in menu order.
const std::vector<Command>& Commands();
/// The row named `name`, or null.
const Command* FindCommand(const std::string& name);
/// The commands whose names are closest to `name` (edit distance, then shared prefix), at most
/// `n`, for "unknown action" messages.
std::vector<std::string> ClosestCommands(const std::string& name, std::size_t n = 3);
/// Parses `text` (everything after the action name) against `cmd`'s arguments. `ui` is asked for
/// toggles and the window's choices (may be null: toggles and window choices are then refused).
/// Returns "" or the refusal, which names the argument: "seeds: N expects a whole number in
/// 1 ... 100000, got 'x'".
std::string ParseCommandArgs(const Command& cmd, const std::string& text, const AppUi* ui,
                             CommandArgs* out);
/// Splits a script line into the action and the rest (trimmed).
void SplitCommandLine(const std::string& line, std::string* action, std::string* rest);

/// `formsim gui --list-commands`: one line per command: name, keys, menu path, arguments.
std::string CommandListText();
/// The README's table of script actions (Markdown), exactly as the README holds it.
std::string CommandTableMarkdown();
/// `formsim gui --script`'s help: the usage of every command, comma-separated.
std::string CommandUsageList();
/// Rows of the F1 help: {keys, help} for every command with a key.
std::vector<std::pair<std::string, std::string>> KeyHelpRows();

}  // namespace formsim::app
