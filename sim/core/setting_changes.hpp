#pragma once
/// \file Settings that changed between two runs, written short: the changes that share a
/// setting's name and its values are told once, with what tells their keys apart in brackets:
/// "k_l 0.15 → 0.5 (R2, R3)" for robots.R2.gains.k_l and robots.R3.gains.k_l. Used for labels
/// that must stay short (a pinned run's legend entry).

#include <string>
#include <vector>

namespace formsim::sim {

/// One changed setting: its full dotted key, the name it is shown by (its shortest unambiguous
/// tail), and its values before and after.
struct SettingChange {
  std::string key, name, from, to;
};

/// The changes joined by ", ", in the order of their first appearance; changes with the same
/// last key segment and the same values are merged into "tail from → to (A, B)", A and B the
/// parts of their keys between the prefix and the suffix they share. "" for no change.
std::string FactorChanges(const std::vector<SettingChange>& changes);

}  // namespace formsim::sim
