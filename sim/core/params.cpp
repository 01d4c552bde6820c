#include "sim/core/params.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace formsim::sim {

namespace {
Param Make(const std::string& key, const std::string& group, const std::string& label,
           Param::Kind kind) {
  Param p;
  p.key = key;
  p.group = group;
  p.label = label;
  p.kind = kind;
  return p;
}
}  // namespace

Param& ParamTable::AddDouble(const std::string& key, const std::string& group,
                             const std::string& label, double* value, double min, double max,
                             const std::string& unit, bool log_scale) {
  Param p = Make(key, group, label, Param::Kind::kDouble);
  p.unit = unit;
  p.d = value;
  p.min = min;
  p.max = max;
  p.log_scale = log_scale;
  params_.push_back(p);
  return params_.back();
}

Param& ParamTable::AddInt(const std::string& key, const std::string& group,
                          const std::string& label, int* value, int min, int max) {
  Param p = Make(key, group, label, Param::Kind::kInt);
  p.i = value;
  p.min = min;
  p.max = max;
  params_.push_back(p);
  return params_.back();
}

Param& ParamTable::AddBool(const std::string& key, const std::string& group,
                           const std::string& label, bool* value) {
  Param p = Make(key, group, label, Param::Kind::kBool);
  p.b = value;
  params_.push_back(p);
  return params_.back();
}

Param& ParamTable::AddChoice(const std::string& key, const std::string& group,
                             const std::string& label, int* index,
                             std::vector<std::string> choices) {
  Param p = Make(key, group, label, Param::Kind::kChoice);
  p.i = index;
  p.choices = std::move(choices);
  p.max = static_cast<double>(p.choices.size()) - 1;
  params_.push_back(p);
  return params_.back();
}

Param* ParamTable::Find(const std::string& key) {
  for (auto& p : params_)
    if (p.key == key) return &p;
  return nullptr;
}

std::string ParamTable::SetFromString(Param& p, const std::string& text) {
  const std::string where = "parameter '" + p.key + "'";
  switch (p.kind) {
    case Param::Kind::kDouble: {
      errno = 0;
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || errno == ERANGE)
        return where + ": expected a number, got '" + text + "'";
      if (!std::isfinite(v)) return where + ": must be finite, got '" + text + "'";
      *p.d = v;
      return "";
    }
    case Param::Kind::kInt: {
      char* end = nullptr;
      const long v = std::strtol(text.c_str(), &end, 10);
      if (end == text.c_str() || *end != '\0') return where + ": expected an integer, got '" + text + "'";
      *p.i = static_cast<int>(v);
      return "";
    }
    case Param::Kind::kBool:
      if (text == "true" || text == "1" || text == "on") *p.b = true;
      else if (text == "false" || text == "0" || text == "off") *p.b = false;
      else return where + ": expected true or false, got '" + text + "'";
      return "";
    case Param::Kind::kChoice:
      for (std::size_t i = 0; i < p.choices.size(); ++i) {
        if (p.choices[i] == text) {
          *p.i = static_cast<int>(i);
          return "";
        }
      }
      return where + ": '" + text + "' is not a valid choice";
  }
  return where + ": unknown kind";
}

std::string ParamTable::ToString(const Param& p) {
  char buf[40];
  switch (p.kind) {
    case Param::Kind::kDouble: std::snprintf(buf, sizeof buf, "%.17g", *p.d); return buf;
    case Param::Kind::kInt: return std::to_string(*p.i);
    case Param::Kind::kBool: return *p.b ? "true" : "false";
    case Param::Kind::kChoice:
      return (*p.i >= 0 && *p.i < static_cast<int>(p.choices.size())) ? p.choices[*p.i] : "";
  }
  return "";
}

}  // namespace formsim::sim
