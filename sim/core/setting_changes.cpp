#include "sim/core/setting_changes.hpp"

#include <algorithm>

namespace formsim::sim {
namespace {

std::string LastSegment(const std::string& key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

// The dotted segments of a key.
std::vector<std::string> Segments(const std::string& key) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    out.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) return out;
    start = dot + 1;
  }
}

// What tells each key of a group apart: its segments between the segments all keys share at
// the front and at the back ("R2" of robots.R2.gains.k_l among robots.R3.gains.k_l).
std::vector<std::string> Distinct(const std::vector<const SettingChange*>& group) {
  std::vector<std::vector<std::string>> segs;
  for (const SettingChange* c : group) segs.push_back(Segments(c->key));
  std::size_t shortest = segs[0].size();
  for (const auto& s : segs) shortest = std::min(shortest, s.size());
  auto same_at = [&](auto index) {
    for (const auto& s : segs)
      if (s[index(s)] != segs[0][index(segs[0])]) return false;
    return true;
  };
  std::size_t front = 0, back = 0;
  while (front < shortest && same_at([&](const auto&) { return front; })) ++front;
  while (back < shortest - front && same_at([&](const auto& s) { return s.size() - 1 - back; }))
    ++back;
  std::vector<std::string> out;
  for (const auto& s : segs) {
    std::string part;
    for (std::size_t i = front; i + back < s.size(); ++i) part += (part.empty() ? "" : ".") + s[i];
    out.push_back(part.empty() ? "?" : part);
  }
  return out;
}

}  // namespace

std::string FactorChanges(const std::vector<SettingChange>& changes) {
  std::vector<bool> done(changes.size(), false);
  std::string out;
  for (std::size_t i = 0; i < changes.size(); ++i) {
    if (done[i]) continue;
    const SettingChange& c = changes[i];
    std::vector<const SettingChange*> group = {&c};
    for (std::size_t j = i + 1; j < changes.size(); ++j)
      if (!done[j] && LastSegment(changes[j].key) == LastSegment(c.key) &&
          changes[j].from == c.from && changes[j].to == c.to) {
        group.push_back(&changes[j]);
        done[j] = true;
      }
    out += out.empty() ? "" : ", ";
    if (group.size() == 1) {
      out += c.name + " " + c.from + " → " + c.to;
      continue;
    }
    std::string which;
    for (const std::string& d : Distinct(group)) which += (which.empty() ? "" : ", ") + d;
    out += LastSegment(c.key) + " " + c.from + " → " + c.to + " (" + which + ")";
  }
  return out;
}

}  // namespace formsim::sim
