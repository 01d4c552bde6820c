#include "sim/study/reproduction_registry.hpp"

#include <algorithm>
#include <stdexcept>

namespace formsim::sim {
namespace {

std::vector<ReproPaper (*)()>& Makers() {
  static std::vector<ReproPaper (*)()> makers;
  return makers;
}

}  // namespace

bool RegisterReproPaper(ReproPaper (*make)()) {
  Makers().push_back(make);
  return true;
}

const std::vector<ReproPaper>& ReproPapers() {
  static const std::vector<ReproPaper> papers = [] {
    std::vector<ReproPaper> v;
    for (auto make : Makers()) v.push_back(make());
    std::stable_sort(v.begin(), v.end(), [](const ReproPaper& a, const ReproPaper& b) {
      return a.number != b.number ? a.number < b.number : a.name < b.name;
    });
    for (const ReproPaper& p : v) CheckPaper(p);
    return v;
  }();
  return papers;
}

const ReproPaper& FindReproPaper(const std::string& name) {
  std::string names;
  for (const ReproPaper& p : ReproPapers()) {
    if (p.name == name) return p;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw std::runtime_error("formsim reproduce: no paper '" + name + "' (papers: " + names + ")");
}

}  // namespace formsim::sim
