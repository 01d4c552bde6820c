/// \file Pinned runs: a run kept as a reference while tuning goes on. A pin is an exact replay of
/// the run's log (the simulation is deterministic), made on a thread of its own so the window
/// stays responsive; it survives resets, seed changes and edits, and goes when unpinned or when
/// another scenario is loaded.
#include <cstdio>

#include "app/gui/history_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/run_output.hpp"

namespace formsim::app {

std::string AppUi::PinReplay(std::shared_ptr<const sim::ScenarioSource> source, sim::RunLog log,
                             long steps, const std::string& origin) {
  auto pin = std::make_unique<PinnedRun>();
  pin->id = next_pin_++;
  pin->origin = origin;
  pin->steps = steps;
  pin->source = source;
  pin->log = log;
  pin->cancel = std::make_shared<std::atomic<bool>>(false);
  auto cancel = pin->cancel;
  pin->job = std::async(std::launch::async, [source, log = std::move(log), steps, cancel]() {
    PinnedRun::Result r;
    try {
      // The history bound of the GUI's runs, so the copy's plots match the live run's.
      sim::RunReplay replay(*source, log, [](sim::Experiment& e) {
        e.mutable_recorder().SetHistoryLimit(sim::kRunHistoryRows);
      });
      if (!replay.AdvanceTo(steps, true, [&] { return cancel->load(); })) {
        r.error = "cancelled";
        return r;
      }
      for (const sim::Param& p : replay.parsed().params.all())
        r.values.emplace_back(p.key, p.Text());
      r.values.emplace_back("seed", std::to_string(replay.exp().setup().seed));
      r.exp = replay.Release();
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    return r;
  });
  sim::SessionEvent note;
  note.kind = sim::SessionEvent::Kind::kNote;
  note.key = "pin";
  note.value = "pin " + std::to_string(pin->id) + ": " + origin;
  note.step = session_->exp().steps();
  record_.Add(note);
  SetStatus("pinned " + origin + " as pin " + std::to_string(pin->id));
  pins_.push_back(std::move(pin));
  return "";
}

std::string AppUi::CmdPin() {
  const sim::Experiment& exp = session_->exp();
  if (exp.steps() == 0) {
    SetStatus("pin: the run has not started (nothing to keep yet)", true);
    return state_.status;
  }
  char origin[64];
  std::snprintf(origin, sizeof origin, "the run at t = %.2f s", exp.time());
  return PinReplay(std::make_shared<sim::ScenarioSource>(session_->source()), session_->run_log(),
                   exp.steps(), origin);
}

std::string AppUi::CmdPinRow(int number) {
  std::string missing;
  const sim::HistoryRow* row = history_->RowOrRefuse("pin-row", number, &missing);
  if (row == nullptr) return missing;
  if (row->source->sha256() != session_->source().sha256() &&
      sim::ParseScenario(*row->source, {}).setup.type != session_->exp().setup().type) {
    const std::string why =
        "pin-row: row " + std::to_string(number) + " is another kind of scenario";
    SetStatus(why, true);
    return why;
  }
  return PinReplay(row->source, row->log, row->steps, "history row " + std::to_string(number));
}

std::string AppUi::CmdUnpin(int id) {
  for (auto it = pins_.begin(); it != pins_.end(); ++it)
    if ((*it)->id == id) {
      pins_.erase(it);
      sim::SessionEvent note;
      note.kind = sim::SessionEvent::Kind::kNote;
      note.key = "unpin";
      note.value = "pin " + std::to_string(id);
      note.step = session_->exp().steps();
      record_.Add(note);
      SetStatus("unpinned pin " + std::to_string(id));
      return "";
    }
  const std::string why = "unpin: no pin " + std::to_string(id);
  SetStatus(why, true);
  return why;
}

std::string AppUi::CmdUnpinAll() {
  const std::size_t n = pins_.size();
  pins_.clear();
  sim::SessionEvent note;
  note.kind = sim::SessionEvent::Kind::kNote;
  note.key = "unpin-all";
  note.step = session_->exp().steps();
  record_.Add(note);
  SetStatus("unpinned " + std::to_string(n) + " run" + (n == 1 ? "" : "s"));
  return "";
}

std::string AppUi::PinLabel(const PinnedRun& pin) const {
  std::string label = "pin " + std::to_string(pin.id);
  if (!pin.ready()) return label + (pin.error.empty() ? " (replaying...)" : " (failed)");
  // Changes shared by several keys told once: "k_l 0.15 → 0.5 (R2, R3)".
  const std::string diff =
      sim::FactorChanges(sim::DifferencesOf(pin.values, CurrentValues(), session_->params()));
  return label + ": " + (diff.empty() ? "same settings" : diff);
}

// The History tab's first part: the pinned runs, each with what differs and its unpin button.
void AppUi::DrawPinnedRuns() {
  ImGui::Text("Pinned runs (%zu)", pins_.size());
  if (!pins_.empty() && ImGui::BeginTable("pins", 3,
                                          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                              ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("pin", ImGuiTableColumnFlags_WidthFixed, 60);
    ImGui::TableSetupColumn("what differs from the current run");
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 60);
    ImGui::TableHeadersRow();
    int unpin = 0;
    for (const auto& p : pins_) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::Text("pin %d", p->id);
      ImGui::TableSetColumnIndex(1);
      const std::string label = PinLabel(*p);
      ImGui::TextWrapped(
          "%s (%s)",
          label.substr(label.find(':') == std::string::npos ? label.size() : label.find(':') + 2)
              .c_str(),
          p->origin.c_str());
      if (!p->error.empty())
        ImGui::TextColored(ImVec4(0.75f, 0.1f, 0.1f, 1), "%s", p->error.c_str());
      ImGui::TableSetColumnIndex(2);
      ImGui::PushID(p->id);
      if (ImGui::SmallButton("unpin")) unpin = p->id;
      ImGui::PopID();
    }
    ImGui::EndTable();
    if (unpin) CmdUnpin(unpin);
  }
  ImGui::Spacing();

}

}  // namespace formsim::app
