#pragma once
/// \file Table headers that never lie about their unit: a header too long for its column is
/// shortened in its name, keeping its bracketed unit whole ("max|e_p… [°]", never
/// "max|e_phi| [r…"), and shows its full text in a tooltip.

#include <functional>
#include <string>
#include <vector>

namespace formsim::app {

/// `label` as it fits in `width` (measured by `measure`): whole when it fits, else its name cut
/// at a character with "…" before its bracketed unit, else "…" and the unit, else "…".
std::string FitHeader(const std::string& label, float width,
                      const std::function<float(const std::string&)>& measure);

/// The header row of the current ImGui table (in place of TableHeadersRow): `labels`, one per
/// column, each fitted to its column, the full text in a tooltip when shortened. `sortable`:
/// room is kept for the sort arrow.
void TableHeaders(const std::vector<std::string>& labels, bool sortable = false);

/// Shades the current table cell as its column's best value (compare and history tables).
void MarkBestCell();

}  // namespace formsim::app
