#include "sim/formation/formation_editing.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sim/core/experiment.hpp"
#include "sim/core/number_format.hpp"
#include "sim/session/session.hpp"

namespace formsim::sim::formation {
namespace {

namespace cf = control::formation;

[[noreturn]] void Refuse(const std::string& why) {
  throw std::runtime_error(why);
}

std::vector<std::string> Words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::vector<std::string> SplitNames(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s + ",") {
    if (c == ',') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  return out;
}

std::string Joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

double Number(const std::string& s, const std::string& what) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || !std::isfinite(v)) Refuse(what + " must be a number, got '" + s + "'");
  return v;
}

cf::FormationLaw Law(const std::string& s) {
  cf::FormationLaw law;
  if (!cf::ParseLaw(s, &law))
    Refuse(std::string("law must be ") + cf::LawName(cf::FormationLaw::kLPhi) +
           " (one leader) or " + cf::LawName(cf::FormationLaw::kLL) + " (two leaders), got '" + s +
           "'");
  return law;
}

cf::ShapeKind Shape(const std::vector<std::string>& w) {
  cf::ShapeKind kind;
  if (w.size() < 2 || !cf::ShapeFromName(w[1], &kind)) {
    std::string names;
    for (const auto& n : cf::ShapeNames()) names += (names.empty() ? "" : ", ") + n;
    Refuse("shape: name one of " + names);
  }
  return kind;
}

struct Text {
  std::string operator()(const AddFollower& c) const {
    return std::string("add ") + cf::LawName(c.law) + " " + Joined(c.leaders) + " " +
           FormatDouble(c.x) + " " + FormatDouble(c.y) + (c.name.empty() ? "" : " " + c.name);
  }
  std::string operator()(const RemoveRobot& c) const { return "remove " + c.name; }
  std::string operator()(const AttachFollower& c) const {
    return "attach " + c.name + " " + cf::LawName(c.law) + " " + Joined(c.leaders);
  }
  std::string operator()(const ApplyShape& c) const {
    return "shape " + cf::ShapeNames()[static_cast<std::size_t>(c.kind)] +
           (c.spacing ? " " + FormatDouble(*c.spacing) : "");
  }
};

}  // namespace

std::string StructureChangeText(const StructureChange& change) {
  return std::visit(Text{}, change.what);
}

StructureChange ParseStructureChange(const std::string& text) {
  const std::vector<std::string> w = Words(text);
  if (w.empty()) Refuse("an empty formation command (add, remove, attach, shape)");
  if (w[0] == "add") {
    if (w.size() < 5 || w.size() > 6) Refuse("add LAW LEADERS X Y [NAME]");
    AddFollower c;
    c.law = Law(w[1]);
    c.leaders = SplitNames(w[2]);
    c.x = Number(w[3], "x");
    c.y = Number(w[4], "y");
    if (w.size() == 6) c.name = w[5];
    return {c};
  }
  if (w[0] == "remove") {
    if (w.size() != 2) Refuse("remove NAME");
    return {RemoveRobot{w[1]}};
  }
  if (w[0] == "attach") {
    if (w.size() != 4) Refuse("attach NAME LAW LEADERS");
    return {AttachFollower{w[1], Law(w[2]), SplitNames(w[3])}};
  }
  if (w[0] == "shape") {
    ApplyShape c;
    c.kind = Shape(w);
    if (w.size() > 2) c.spacing = Number(w[2], "shape spacing");
    return {c};
  }
  Refuse("unknown formation command '" + w[0] + "' (add, remove, attach, shape)");
}

const FormationEditing* EditingOf(const Experiment& exp) {
  return exp.As<FormationEditing>();
}

namespace {

const FormationEditing& Editing(const Experiment& exp) {
  const FormationEditing* editing = EditingOf(exp);
  if (editing == nullptr) Refuse("this kind of scenario offers no structural changes");
  return *editing;
}

}  // namespace

std::string Restructure(Session& session, const StructureChange& change,
                        const std::string& origin) {
  return session.Restructure(
      StructureChangeText(change),
      [&change](const Experiment& now, const std::string& text) {
        return Editing(now).Restructured(text, change);
      },
      origin);
}

std::string Restructure(Session& session, const std::string& command, const std::string& origin) {
  return session.Restructure(
      command,
      [&command](const Experiment& now, const std::string& text) {
        const FormationEditing& editing = Editing(now);
        if (Words(command).empty()) return editing.PlacedText(text);
        return editing.Restructured(text, ParseStructureChange(command));
      },
      origin);
}

}  // namespace formsim::sim::formation
