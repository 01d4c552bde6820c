#pragma once
/// \file Limits on what a YAML text may expand to, checked on yaml-cpp's event stream before
/// the document is built. An alias stands for a copy of its anchor's whole subtree, so a few
/// hundred bytes of nested aliases (the "billion laughs" document: nine levels of nine aliases
/// each, 9^9 nodes) make every walk over the tree take hours. The check counts each node as
/// often as the aliases repeat it, without expanding anything, and refuses the document at the
/// alias that crosses a limit.

#include <cstddef>
#include <string>

namespace formsim::sim {

/// The most nodes a YAML document may expand to, aliases counted as copies of their anchor
/// (the largest shipped scenario, 1000 robots, has about 40,000).
constexpr std::size_t kMaxYamlNodes = 1000000;
/// The deepest nesting of collections a document may reach, aliases expanded.
constexpr int kMaxYamlDepth = 64;

/// Checks the first document of `text` against kMaxYamlNodes and kMaxYamlDepth, and refuses an
/// alias that refers to a node containing it (a cycle). Throws ScenarioError at `file`:line:col
/// of the offending alias (or node), e.g. "file:12:8: alias '*b' makes the document expand to
/// more than 1000000 nodes (aliases count as copies of what they name)". yaml-cpp's syntax
/// errors are thrown as YAML::ParserException (LoadYamlText words them).
void CheckYamlLimits(const std::string& text, const std::string& file);

/// The number of nodes the first document of `text` expands to (aliases as copies), counting
/// stops just above `stop_after`. For tests and the fuzz harnesses.
std::size_t ExpandedYamlNodes(const std::string& text, std::size_t stop_after = kMaxYamlNodes);

}  // namespace formsim::sim
