#pragma once
/// \file Writing values back into a scenario's own text: only the edited values change,
/// comments and layout stay. Used by Save in the GUI and by `formsim tune`'s best.yaml.

#include <string>
#include <utility>
#include <vector>

namespace formsim::sim {

/// Sets each `path = value` (dotted key paths, list items by name or index; values as YAML
/// text) in `text`, changing only the characters of the values concerned. A key that is not
/// in the text is inserted into its nearest existing map (block or flow), with the missing
/// intermediate maps written inline. Returns false, with the reason in *why, when a value
/// cannot be placed by editing the text (the caller then writes the whole tree).
bool PatchYamlText(const std::string& text, const std::vector<std::pair<std::string, std::string>>& edits,
                   std::string* out, std::string* why);

}  // namespace formsim::sim
