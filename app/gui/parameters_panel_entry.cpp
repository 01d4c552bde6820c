/// \file The Parameters panel's value entry commands (app/gui/value_entry.hpp): what a double-click, the keyboard
/// and the mouse wheel do to a tunable's field, for scripts and the command table. The field
/// itself is drawn by the Parameters panel (app/gui/parameters_panel.cpp).
#include <imgui.h>

#include "app/gui/parameters_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/display_unit.hpp"
#include "sim/session/session.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

// The tunable `key` when it is a number; else null with `why` said.
const sim::Param* NumberParam(const sim::Session& s, const std::string& action,
                              const std::string& key, std::string* why) {
  const sim::Param* p = s.params().Find(key);
  if (p == nullptr) {
    *why = action + ": no tunable '" + key + "'";
    return nullptr;
  }
  if (p->kind != sim::Param::Kind::kDouble && p->kind != sim::Param::Kind::kInt) {
    *why = action + ": '" + key + "' is a switch or a choice, not a number (use edit)";
    return nullptr;
  }
  return p;
}

}  // namespace

std::string ParametersPanel::CmdFieldOpen(const std::string& key) {
  std::string why;
  const sim::Param* p = NumberParam(ctx_.session(), "field-open", key, &why);
  if (p == nullptr) {
    ctx_.SetStatus(why, true);
    return why;
  }
  value_entry_.Open(
      key, ParamEntryText(*p, ctx_.session().EffectiveValue(key), ctx_.state->settings.degrees));
  focus_param_ = key;  // opens its section and scrolls to it
  return "";
}

std::string ParametersPanel::CmdFieldType(const std::string& text) {
  if (value_entry_.key().empty()) {
    const std::string why = "field-type: no value field is open (field-open KEY first)";
    ctx_.SetStatus(why, true);
    return why;
  }
  ImGui::GetIO().AddInputCharactersUTF8(text.c_str());
  return "";
}

std::string ParametersPanel::CmdFieldKey(bool commit) {
  if (value_entry_.key().empty()) {
    const std::string why = std::string(commit ? "field-enter" : "field-escape") +
                            ": no value field is open (field-open KEY first)";
    ctx_.SetStatus(why, true);
    return why;
  }
  ValueEntry& entry = value_entry_;
  const sim::Param* p = ctx_.session().params().Find(entry.key());
  if (!commit || p == nullptr || entry.Unchanged()) {
    entry.Close();  // Esc, or Enter on the text it opened with: nothing applied
    return "";
  }
  // Applied once, or refused with the loader's reason: the field stays open and red, and
  // nothing is applied.
  const double scale = p->kind == sim::Param::Kind::kDouble
                           ? ShownUnit(p->tune.unit, ctx_.state->settings.degrees).scale
                           : 1.0;
  const std::string err = CmdEdit(entry.key(), entry.StoredText(scale));
  if (err.empty())
    entry.Close();
  else
    entry.Refused(err);
  return err;
}

std::string ParametersPanel::CmdFieldWheel(const std::string& key, int steps) {
  std::string why;
  const sim::Param* p = NumberParam(ctx_.session(), "field-wheel", key, &why);
  if (p == nullptr) {
    ctx_.SetStatus(why, true);
    return why;
  }
  double v = p->value;
  sim::ParseFiniteDouble(ctx_.session().EffectiveValue(key), &v);
  const double scale = p->kind == sim::Param::Kind::kDouble
                           ? ShownUnit(p->tune.unit, ctx_.state->settings.degrees).scale
                           : 1.0;
  return CmdEdit(key, FineStep(*p, v, steps, scale));
}

}  // namespace formsim::app
