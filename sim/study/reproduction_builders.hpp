#pragma once
/// \file Builders for a paper's reproduction tables (sim/<kind>/<kind>_paper.cpp): columns (a
/// header, a metric path, how to show it over the seeds), rows and numbers as short text.

#include <string>
#include <utility>
#include <vector>

#include "sim/core/number_format.hpp"
#include "sim/study/reproduction.hpp"

namespace formsim::sim::repro {

// Column builders: a header, a metric ("{}": the row's key), how to show it.
inline ReproColumn Stat(const std::string& header, const std::string& metric, CellStat stat,
                        double scale = 1.0, int digits = 1) {
  ReproColumn c;
  c.header = header;
  c.metric = metric;
  c.stat = stat;
  c.scale = scale;
  c.digits = digits;
  return c;
}
inline ReproColumn Sci(const std::string& header, const std::string& metric) {
  ReproColumn c = Stat(header, metric, CellStat::kMeanStd, 1.0, 2);
  c.sci = true;
  return c;
}
inline ReproColumn Count(const std::string& header, const std::string& metric) {
  return Stat(header, metric, CellStat::kCount);
}
inline ReproColumn Below(const std::string& header, const std::string& metric,
                         const std::string& versus) {
  ReproColumn c = Stat(header, metric, CellStat::kBelow);
  c.versus = versus;
  return c;
}
inline ReproColumn InCase(ReproColumn c, const std::string& case_id) {
  c.case_id = case_id;
  return c;
}
inline ReproRow Row(std::vector<std::string> labels, const std::string& case_id,
                    const std::string& key = "", std::vector<std::string> texts = {}) {
  return ReproRow{std::move(labels), case_id, key, std::move(texts)};
}
inline ReproRow TextRow(std::vector<std::string> labels, std::vector<std::string> texts) {
  return ReproRow{std::move(labels), "", "", std::move(texts)};
}

inline std::string Str(double v) {
  return FormatFixed(v, 6, /*trim=*/true);
}

}  // namespace formsim::sim::repro
