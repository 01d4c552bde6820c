#include "sim/core/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/core/number_format.hpp"

namespace formsim::sim {

bool PathMatches(const std::string& pattern, const std::string& path) {
  // Glob with '*' only: iterative, backtracking to the last star.
  std::size_t p = 0, s = 0, star = std::string::npos, mark = 0;
  while (s < path.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = s;
    } else if (p < pattern.size() && pattern[p] == path[s]) {
      ++p, ++s;
    } else if (star != std::string::npos) {
      p = star + 1;
      s = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

bool PathCaptures(const std::string& pattern, const std::string& path,
                  std::vector<std::string>* captures) {
  // Shortest match for each '*' from the left (patterns are a few segments long): try each
  // length for the first star and match the rest recursively.
  const std::size_t star = pattern.find('*');
  if (star == std::string::npos) return pattern == path;
  if (path.compare(0, star, pattern, 0, star) != 0 || path.size() < star) return false;
  const std::string rest = pattern.substr(star + 1);
  for (std::size_t len = 0; star + len <= path.size(); ++len) {
    std::vector<std::string> more;
    if (PathCaptures(rest, path.substr(star + len), &more)) {
      captures->clear();
      captures->push_back(path.substr(star, len));
      captures->insert(captures->end(), more.begin(), more.end());
      return true;
    }
  }
  return false;
}

std::string MetricInfo::AxisLabel(const std::string& fallback) const {
  const std::string base = label.empty() ? fallback : label;
  return unit.empty() ? base : base + " [" + unit + "]";
}

void Metrics::Describe(const std::string& pattern, const std::string& label,
                       const std::string& unit, Better better) {
  descriptions_.push_back({pattern, label, unit});
  if (better != Better::kNone) SetBetter(pattern, better);
}

MetricInfo Metrics::InfoOf(const std::string& path) const {
  MetricInfo info;
  info.better = BetterOf(path);
  const Entry* e = Lookup(path);
  if (e != nullptr && e->is_setting) info.role = MetricRole::kSetting;
  for (auto it = descriptions_.rbegin(); it != descriptions_.rend(); ++it) {
    std::vector<std::string> caps;
    if (!PathCaptures(it->pattern, path, &caps)) continue;
    info.label = it->label;
    for (std::size_t k = 0; k < caps.size(); ++k) {
      const std::string mark = "{" + std::to_string(k + 1) + "}";
      for (std::size_t at = info.label.find(mark); at != std::string::npos;
           at = info.label.find(mark, at + caps[k].size()))
        info.label.replace(at, mark.size(), caps[k]);
    }
    info.unit = it->unit;
    break;
  }
  if (info.role == MetricRole::kResult)
    for (std::size_t h = 0; h < headlines_.size(); ++h)
      if (PathMatches(headlines_[h].pattern, path)) {
        info.headline = static_cast<int>(h) + 1;
        break;
      }
  return info;
}

Better Metrics::BetterOf(const std::string& path) const {
  for (auto it = better_.rbegin(); it != better_.rend(); ++it)
    if (PathMatches(it->first, path)) return it->second;
  return Better::kNone;
}

std::vector<Metrics::HeadlineValue> Metrics::Headlines() const {
  std::vector<HeadlineValue> out;
  if (headlines_.empty()) {
    for (const Entry& e : entries_) {
      if (e.is_text || e.is_flag || e.is_setting) continue;
      out.push_back({e.path, "", e.value, BetterOf(e.path)});
      if (out.size() == 3) break;
    }
    return out;
  }
  for (const Headline& h : headlines_) {
    HeadlineValue v{h.label, h.format, std::numeric_limits<double>::quiet_NaN(), Better::kNone};
    bool first = true;
    for (const Entry& e : entries_) {
      if (e.is_text || !PathMatches(h.pattern, e.path)) continue;
      if (first) v.better = BetterOf(e.path);
      switch (h.combine) {
        case Combine::kValue:
          if (first) v.value = e.value;
          break;
        case Combine::kMax:
          v.value = first || std::isnan(v.value) || e.value > v.value ? e.value : v.value;
          break;
        case Combine::kSum:
          v.value = first ? e.value : v.value + e.value;
          break;
      }
      first = false;
    }
    out.push_back(v);
  }
  return out;
}

Metrics::Entry* Metrics::Slot(const std::string& path) {
  const auto [it, added] = index_.emplace(path, entries_.size());
  if (added) entries_.push_back(Entry{path, false, false, false, 0.0, ""});
  return &entries_[it->second];
}

const Metrics::Entry* Metrics::Lookup(const std::string& path) const {
  const auto it = index_.find(path);
  return it == index_.end() ? nullptr : &entries_[it->second];
}

void Metrics::Set(const std::string& path, double value) {
  Entry* e = Slot(path);
  e->is_text = false;
  e->is_flag = false;
  e->is_setting = false;
  e->value = value;
}

void Metrics::SetFlag(const std::string& path, bool value) {
  Entry* e = Slot(path);
  e->is_text = false;
  e->is_setting = false;
  e->is_flag = true;
  e->value = value ? 1.0 : 0.0;
}

void Metrics::SetSetting(const std::string& path, double value) {
  Set(path, value);
  Slot(path)->is_setting = true;
}

void Metrics::SetText(const std::string& path, const std::string& text) {
  Entry* e = Slot(path);
  e->is_text = true;
  e->text = text;
}

Json Metrics::ToJson() const {
  Json root = Json::Object();
  for (const Entry& e : entries_) {
    Json* node = &root;
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = e.path.find('.', start);
      const std::string seg = e.path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (dot == std::string::npos) {
        (*node)[seg] = e.is_text ? Json(e.text) : e.is_flag ? Json(e.value != 0) : Json(e.value);
        break;
      }
      node = &(*node)[seg];
      start = dot + 1;
    }
  }
  return root;
}

std::vector<std::pair<std::string, double>> Metrics::Scalars() const {
  std::vector<std::pair<std::string, double>> out;
  for (const Entry& e : entries_)
    if (!e.is_text) out.emplace_back(e.path, e.value);
  return out;
}

std::vector<std::pair<std::string, double>> Metrics::Scalars(MetricRole role) const {
  std::vector<std::pair<std::string, double>> out;
  for (const Entry& e : entries_)
    if (!e.is_text && e.is_setting == (role == MetricRole::kSetting)) out.emplace_back(e.path, e.value);
  return out;
}

const double* Metrics::Find(const std::string& path) const {
  const Entry* e = Lookup(path);
  return e != nullptr && !e->is_text ? &e->value : nullptr;
}

std::string Metrics::Cell(const std::string& path, const std::string& format) const {
  const Entry* e = Lookup(path);
  if (e == nullptr) return "-";
  if (e->is_text) return e->text;
  if (e->is_flag) return e->value != 0 ? "yes" : "no";
  if (format.empty()) return FormatDouble(e->value);
  return Sprintf(format.c_str(), e->value);
}

std::vector<TableSpec> Metrics::GuiTables() const {
  std::vector<TableSpec> out;
  for (const Table& t : tables_) {
    TableSpec s;
    s.title = t.title;
    s.header.push_back(t.row_header);
    for (const Column& c : t.columns) s.header.push_back(c.header);
    for (const auto& [label, prefix] : t.rows) {
      std::vector<std::string> row = {label};
      for (const Column& c : t.columns)
        row.push_back(Cell(prefix.empty() ? c.path : prefix + "." + c.path, c.format));
      s.rows.push_back(std::move(row));
    }
    out.push_back(std::move(s));
  }
  return out;
}

std::string Metrics::Text() const {
  std::string out;
  for (const auto& n : notes_) out += n + "\n";
  for (const TableSpec& t : GuiTables()) {
    std::vector<std::size_t> width(t.header.size(), 0);
    auto grow = [&](const std::vector<std::string>& row) {
      for (std::size_t i = 0; i < row.size() && i < width.size(); ++i)
        width[i] = std::max(width[i], row[i].size());
    };
    grow(t.header);
    for (const auto& r : t.rows) grow(r);
    auto line = [&](const std::vector<std::string>& row) {
      std::string l;
      for (std::size_t i = 0; i < row.size(); ++i) {
        const std::string pad(width[i] - std::min(width[i], row[i].size()), ' ');
        // First column left-aligned (names), numbers right-aligned.
        l += i == 0 ? row[i] + pad : pad + row[i];
        if (i + 1 < row.size()) l += "  ";
      }
      return l + "\n";
    };
    if (!t.title.empty()) out += t.title + "\n";
    out += line(t.header);
    for (const auto& r : t.rows) out += line(r);
  }
  return out;
}

}  // namespace formsim::sim
