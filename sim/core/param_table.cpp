#include "sim/core/param_table.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>

#include "sim/core/number_format.hpp"

namespace formsim::sim {

std::string Tune::Check(double v) const {
  if (!std::isfinite(v)) return "must be a finite number";
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  if (lo_ok && hi_ok) return "";
  return "must be " + ValidityText();
}

std::string Tune::ValidityText() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return std::string("in ") + (lo_open ? "(" : "[") + FormatDouble(lo) + ", " + FormatDouble(hi) +
           (hi_open ? ")" : "]");
  if (has_lo) return std::string(lo_open ? "> " : ">= ") + FormatDouble(lo);
  if (has_hi) return std::string(hi_open ? "< " : "<= ") + FormatDouble(hi);
  return "any finite number";
}

void Tune::CheckDeclaration(const std::string& key) const {
  const bool has_slider = std::isfinite(slider_lo) || std::isfinite(slider_hi);
  if (!has_slider) return;
  if (!(slider_lo < slider_hi))
    throw std::logic_error("tunable '" + key + "': slider range is empty");
  if (!Check(slider_lo).empty() || !Check(slider_hi).empty())
    throw std::logic_error("tunable '" + key + "': slider range [" + FormatDouble(slider_lo) +
                           ", " + FormatDouble(slider_hi) + "] leaves the valid range " +
                           ValidityText());
  if (log_scale && !(slider_lo > 0))
    throw std::logic_error("tunable '" + key + "': a log slider needs a positive minimum");
}

namespace {

double ClampToSlider(double v) {
  return std::clamp(v, -kSliderLimit, kSliderLimit);
}

// A default slider when none is declared: the validity where it is finite, else a span around
// the value that stays valid. Always finite and within ±kSliderLimit (ImGui asserts on a
// slider range beyond half the largest double, and 1e308 + 1e308 is infinite).
double DerivedEnd(const Param& p, bool upper) {
  const Tune& t = p.tune;
  const double end = upper ? t.slider_hi : t.slider_lo;
  if (std::isfinite(end)) return ClampToSlider(end);
  const double bound = upper ? t.hi : t.lo;
  if (std::isfinite(bound)) return ClampToSlider(bound);
  const double v = std::isfinite(p.value) ? ClampToSlider(p.value) : 0.0;
  const double span = std::min(kSliderLimit, std::max(1.0, 2.0 * std::abs(v)));
  return ClampToSlider(upper ? v + span : v - span);
}

}  // namespace

double Param::slider_min() const {
  if (kind == Kind::kBool) return 0;
  if (kind == Kind::kChoice) return 0;
  return DerivedEnd(*this, false);
}

double Param::slider_max() const {
  if (kind == Kind::kBool) return 1;
  if (kind == Kind::kChoice) return static_cast<double>(choices.size()) - 1;
  return DerivedEnd(*this, true);
}

std::string Param::Text() const {
  switch (kind) {
    case Kind::kDouble: return FormatDouble(value);
    case Kind::kInt: return std::to_string(static_cast<long long>(value));
    case Kind::kBool: return value != 0 ? "true" : "false";
    case Kind::kChoice: {
      const int i = static_cast<int>(value);
      return i >= 0 && i < static_cast<int>(choices.size()) ? choices[i] : "";
    }
  }
  return "";
}

std::string Param::Parse(const std::string& text, std::string* canonical) const {
  switch (kind) {
    case Kind::kDouble: {
      double v = 0;
      if (!ParseFiniteDouble(text, &v)) return "expected a finite number, got '" + text + "'";
      const std::string err = tune.Check(v);
      if (!err.empty()) return err;
      *canonical = FormatDouble(v);
      return "";
    }
    case Kind::kInt: {
      long long v = 0;
      if (!ParseInteger(text, -2147483647LL, 2147483647LL, &v))
        return "expected an integer, got '" + text + "'";
      const std::string err = tune.Check(static_cast<double>(v));
      if (!err.empty()) return err;
      *canonical = std::to_string(v);
      return "";
    }
    case Kind::kBool:
      if (text == "true" || text == "false") {
        *canonical = text;
        return "";
      }
      return "expected true or false, got '" + text + "'";
    case Kind::kChoice:
      for (const auto& c : choices)
        if (c == text) {
          *canonical = text;
          return "";
        }
      {
        std::string allowed;
        for (const auto& c : choices) allowed += (allowed.empty() ? "" : ", ") + c;
        return "'" + text + "' is not one of: " + allowed;
      }
  }
  return "unknown parameter kind";
}

void ParamTable::Add(Param p) {
  static std::atomic<std::uint64_t> next{1};
  revision_ = next.fetch_add(1, std::memory_order_relaxed);
  const auto [it, inserted] = index_.emplace(p.key, params_.size());
  if (!inserted) {
    params_[it->second] = std::move(p);  // read twice (e.g. a noise block resolved again): keep the latest
    return;
  }
  params_.push_back(std::move(p));
}

const Param* ParamTable::Find(const std::string& key) const {
  const auto it = index_.find(key);
  return it == index_.end() ? nullptr : &params_[it->second];
}

}  // namespace formsim::sim
