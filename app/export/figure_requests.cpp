#include "app/export/figure_requests.hpp"

#include <stdexcept>

#include "app/export/figure_data.hpp"
#include "sim/session/session.hpp"

namespace formsim::app {

std::set<std::string> ParseFigureNames(const std::string& list, const std::string& flag) {
  std::set<std::string> names;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    std::string name = list.substr(start, end - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (name.empty())
      throw std::runtime_error(flag + " '" + list +
                               "': give figure names separated by commas (an empty name)");
    names.insert(name);
    start = end + 1;
  }
  return names;
}

std::vector<sim::FigureSpec> ProbeFigures(const std::string& file,
                                          const std::vector<sim::Override>& overrides) {
  sim::Session probe(file, overrides);
  if (!probe.exp().finished()) probe.exp().Step();
  return probe.exp().Figures();
}

void CheckFigureRequests(const std::vector<sim::FigureSpec>& figures,
                         const std::set<std::string>& log_y, const std::string& flag) {
  for (const sim::FigureSpec& f : figures)
    if (const std::string e = FigureMarkupError(f); !e.empty())
      throw std::runtime_error("figure '" + f.id + "' " + e);
  std::set<std::string> ids;  // several scenarios may share figure names
  for (const sim::FigureSpec& f : figures)
    if (IsTimePlot(f)) ids.insert(f.id);
  for (const std::string& name : log_y) {
    if (ids.count(name)) continue;
    std::string list;
    for (const std::string& id : ids) list += (list.empty() ? "" : ", ") + id;
    throw std::runtime_error(flag + " '" + name +
                             "': no time plot of that name (the time plots: " + list + ")");
  }
}

}  // namespace formsim::app
