#pragma once
/// \file The command-line reference generated from the CLI11 definitions themselves: the man page
/// (formsim.1), the bash completion and docs/cli.md. Made at build time by the hidden command
/// `formsim reference --format man|bash|markdown`, so none of them can drift from `--help`.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace formsim::app {

/// One option or positional argument of a command, as its --help shows it.
struct OptionDoc {
  std::vector<std::string> names;  ///< "-q", "--quiet"; a positional: its name ("scenario")
  std::string value;               ///< the value's label ("TEXT", "INT"); "" for a flag
  std::string description;
  bool positional = false;
  bool required = false;
  bool repeated = false;  ///< takes several values (--set a=1 b=2) or may be given again
};

/// One command ("run", "sweep collect") with its options.
struct CommandDoc {
  std::string path;  ///< "run", "sweep collect"; "" for formsim itself
  std::string description;
  std::vector<OptionDoc> positionals;
  std::vector<OptionDoc> options;  ///< --help included
  std::vector<std::string> subcommands;  ///< the names of its visible subcommands
};

/// Every visible command of `app`, depth first (formsim itself first); hidden commands and
/// options (empty group) are left out.
std::vector<CommandDoc> DescribeCommands(const CLI::App& app);

/// The man page in roff (man(7)), section 1.
std::string ManPage(const std::vector<CommandDoc>& commands, const std::string& version);
/// A bash completion script (`complete -F _formsim formsim`): commands, their options, scenario
/// and lesson names (from `formsim list --names`), themes and file names for path options.
std::string BashCompletion(const std::vector<CommandDoc>& commands);
/// docs/cli.md: one section per command with a table of its options.
std::string CliMarkdown(const std::vector<CommandDoc>& commands, const std::string& version);

}  // namespace formsim::app
