/// \file The Compare panel (app/gui/compare_panel.hpp): pinned runs and the Compare section.
/// A pin is an exact replay of the run's log (the simulation is deterministic), made on a
/// thread of its own so the window stays responsive; it survives resets, seed changes and
/// edits, and goes when unpinned or when another scenario is loaded.
#include "app/gui/compare_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/fitted_field.hpp"
#include "app/gui/flow_layout.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/theme.hpp"
#include "app/render/world_view.hpp"
#include "sim/core/background.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/wall_clock.hpp"
#include "sim/session/session.hpp"
#include "sim/session/session_record.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {

namespace {

using sim::WallSeconds;

}  // namespace

RunValues CurrentValues(const sim::Session& session) {
  RunValues v;
  for (const sim::Param& p : session.params().all()) v.emplace_back(p.key, p.Text());
  v.emplace_back("seed", std::to_string(session.seed()));
  return v;
}

void ComparePanel::Note(const std::string& key, const std::string& value) {
  sim::SessionEvent note;
  note.kind = sim::SessionEvent::Kind::kNote;
  note.key = key;
  note.value = value;
  note.step = ctx_.session().exp().steps();
  ctx_.record->Add(note);
}

std::string ComparePanel::PinReplay(std::shared_ptr<const sim::ScenarioSource> source, sim::RunLog log,
                             long steps, const std::string& origin) {
  auto pin = std::make_unique<PinnedRun>();
  pin->id = next_pin_++;
  pin->origin = origin;
  pin->steps = steps;
  pin->source = source;
  pin->log = log;
  pin->cancel = std::make_shared<std::atomic<bool>>(false);
  auto cancel = pin->cancel;
  pin->job = sim::StartBackground([source, log = std::move(log), steps, cancel]() {
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
  Note("pin", "pin " + std::to_string(pin->id) + ": " + origin);
  ctx_.SetStatus("pinned " + origin + " as pin " + std::to_string(pin->id));
  pins_.push_back(std::move(pin));
  return "";
}

std::string ComparePanel::CmdPin() {
  const sim::Experiment& exp = ctx_.session().exp();
  if (exp.steps() == 0) {
    ctx_.SetStatus("pin: the run has not started (nothing to keep yet)", true);
    return ctx_.state->status;
  }
  const std::string origin = "the run at " + sim::FormatSimTime(exp.time());
  return PinReplay(std::make_shared<sim::ScenarioSource>(ctx_.session().source()), ctx_.session().run_log(),
                   exp.steps(), origin);
}

std::string ComparePanel::CmdPinRow(int number) {
  std::string missing;
  const sim::HistoryRow* row = ctx_.Find<HistoryPanel>()->RowOrRefuse("pin-row", number, &missing);
  if (row == nullptr) return missing;
  if (row->source->sha256() != ctx_.session().source().sha256() &&
      sim::ParseScenario(*row->source, {}).setup.type != ctx_.session().exp().setup().type) {
    const std::string why =
        "pin-row: row " + std::to_string(number) + " is another kind of scenario";
    ctx_.SetStatus(why, true);
    return why;
  }
  return PinReplay(row->source, row->log, row->steps, "history row " + std::to_string(number));
}

std::string ComparePanel::CmdUnpin(int id) {
  for (auto it = pins_.begin(); it != pins_.end(); ++it)
    if ((*it)->id == id) {
      pins_.erase(it);
      Note("unpin", "pin " + std::to_string(id));
      ctx_.SetStatus("unpinned pin " + std::to_string(id));
      return "";
    }
  const std::string why = "unpin: no pin " + std::to_string(id);
  ctx_.SetStatus(why, true);
  return why;
}

std::string ComparePanel::CmdUnpinAll() {
  const std::size_t n = pins_.size();
  pins_.clear();
  Note("unpin-all", "");
  ctx_.SetStatus("unpinned " + std::to_string(n) + " run" + (n == 1 ? "" : "s"));
  return "";
}

std::string ComparePanel::PinLabel(const PinnedRun& pin) const {
  std::string label = "pin " + std::to_string(pin.id);
  if (!pin.ready()) return label + (pin.error.empty() ? " (replaying...)" : " (failed)");
  // Changes shared by several keys told once: "k_l 0.15 → 0.5 (R2, R3)".
  const std::string diff =
      sim::FactorChanges(sim::DifferencesOf(pin.values, CurrentValues(ctx_.session()), ctx_.session().params()));
  return label + ": " + (diff.empty() ? "same settings" : diff);
}

// The History tab's first part: the pinned runs, each with what differs and its unpin button.
void ComparePanel::DrawPinnedRuns() {
  ImGui::Text("%s", sim::Sprintf("Pinned runs (%zu)", pins_.size()).c_str());
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
      ImGui::Text("%s", sim::Sprintf("pin %d", p->id).c_str());
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

void ComparePanel::Draw(const Fonts&) {
  if (ImGui::Button("Pin")) CmdPin();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Keep this run as a reference: dashed in every plot, faded in the world\n"
        "view, a column of the comparison table");
  SameLineIfFits(ButtonWidth("Unpin all"));
  ImGui::BeginDisabled(pins_.empty());
  if (ImGui::Button("Unpin all")) CmdUnpinAll();
  ImGui::EndDisabled();
  const std::string pinned = std::to_string(pins_.size()) + " pinned (History tab)";
  SameLineIfFits(TextWidth(pinned.c_str()));
  ImGui::TextDisabled("%s", pinned.c_str());

  // Monte Carlo: the count, Run or Cancel, and a bar that is always there.
  const bool running = mc_.run && !mc_.run->finished();
  ImGui::SetNextItemWidth(90);
  ImGui::BeginDisabled(running);
  ImGui::InputInt("##seeds", &mc_seeds_, 1, 10);
  mc_seeds_ = std::clamp(mc_seeds_, 1, 100000);
  const std::string run_label = "Run " + std::to_string(mc_seeds_) + " seeds";
  SameLineIfFits(ButtonWidth(run_label.c_str()));
  if (ImGui::Button(run_label.c_str())) CmdSeeds(mc_seeds_);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The current settings over seeds 1..N in the background: bands on every\n"
        "time plot, mean ± σ in the comparison table (as formsim sweep --seeds 1..N)");
  SameLineIfFits(ButtonWidth("Cancel"));
  ImGui::BeginDisabled(!running);
  if (ImGui::Button("Cancel")) CmdCancelSeeds();
  ImGui::EndDisabled();
  float fraction = 0;
  std::string bar = "no Monte Carlo yet";
  if (mc_.run) {
    const sim::SweepProgress p = mc_.run->progress();
    fraction = p.total ? static_cast<float>(p.done) / static_cast<float>(p.total) : 1.0f;
    bar = sim::Sprintf("%zu / %zu seeds%s: ", p.done, p.total,
                       running                                    ? ""
                       : mc_.run->cancelled() && p.done < p.total ? " (cancelled)"
                                                                  : "") +
          mc_.settings;
  }
  ImGui::ProgressBar(fraction, ImVec2(-1, 0), bar.c_str());
  if (mc_.run && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", bar.c_str());

  // Undo / redo of edits (Ctrl+Z / Ctrl+Y).
  ImGui::BeginDisabled(!ctx_.session().can_undo());
  if (ImGui::Button("Undo")) ctx_.run("undo");
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Ctrl+Z: %s",
                      ctx_.session().can_undo() ? ctx_.session().UndoText().c_str() : "nothing");
  SameLineIfFits(ButtonWidth("Redo"));
  ImGui::BeginDisabled(!ctx_.session().can_redo());
  if (ImGui::Button("Redo")) ctx_.run("redo");
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Ctrl+Y: %s",
                      ctx_.session().can_redo() ? ctx_.session().RedoText().c_str() : "nothing");
  const std::string edits =
      std::to_string(ctx_.session().accepted_edits()) + " edits since loading";
  SameLineIfFits(TextWidth(edits.c_str()));
  ImGui::TextDisabled("%s", edits.c_str());

  ImGui::SetNextItemWidth(WidthBeside("Save session"));
  FittedInputText("##session", ctx_.state->session_path, sizeof(ctx_.state->session_path));
  ImGui::SameLine();
  if (ImGui::Button("Save session"))
    ctx_.run(std::string("save-session ") + ctx_.state->session_path);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Everything done so far, step by step (replay it headless:\n"
        "formsim replay FILE --out DIR)");
}


bool ComparePanel::SeedsRunning() const {
  return mc_.run && !mc_.run->finished();
}

bool ComparePanel::Busy() const {
  for (const auto& p : pins_)
    if (p->job.valid()) return true;
  if (mc_.run && (!mc_.run->finished() || !mc_.tables)) return true;
  return span_.Busy();
}

void ComparePanel::Update() {
  // Pins whose replay has finished.
  for (auto& p : pins_) {
    if (!p->job.valid() || p->job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
      continue;
    PinnedRun::Result r = p->job.get();
    if (!r.error.empty()) {
      p->error = r.error;
      ctx_.SetStatus("pin " + std::to_string(p->id) + " failed: " + r.error, true);
      continue;
    }
    p->exp = std::move(r.exp);
    p->values = std::move(r.values);
    p->results = p->exp->Results();
  }
  // The Monte Carlo: its spread now and then while it runs, everything once it is done.
  if (!mc_.run) return;
  const double now = WallSeconds();
  const bool done = mc_.run->finished();
  if ((done && !mc_.tables) || now - mc_.bands_at > 0.5) {
    mc_.bands = mc_.run->Bands();
    mc_.headlines = mc_.run->HeadlineStats();
    mc_.bands_at = now;
  }
  if (done && !mc_.tables) {
    mc_.tables = mc_.run->Tables();
    const sim::SweepProgress p = mc_.run->progress();
    const std::string err = mc_.run->error();
    if (!err.empty())
      ctx_.SetStatus("Monte Carlo failed: " + err, true);
    else
      ctx_.SetStatus(std::string(mc_.run->cancelled() && p.done < p.total
                                     ? "Monte Carlo cancelled: "
                                     : "Monte Carlo done: ") +
                     std::to_string(p.done) + " of " + std::to_string(p.total) + " seeds" +
                     (p.failed ? ", " + std::to_string(p.failed) + " failed" : ""));
  }
}

void ComparePanel::Clear() {
  pins_.clear();  // each pin's destructor waits for its replay, which stops at once
  span_.Clear();
  next_pin_ = 1;
  mc_ = MonteCarloState();
}

std::string ComparePanel::Decoration() const {
  std::string d = std::to_string(mc_.bands.runs) + "/" + std::to_string(mc_.bands_at);
  for (const auto& pin : pins_)
    if (pin->ready()) d += "|" + std::to_string(pin->id) + ":" + PinLabel(*pin);
  return d;
}

void ComparePanel::AddWorldOverlays(WorldViewOptions& opt) const {
  for (const auto& p : pins_)
    if (p->ready())
      opt.overlays.push_back({p->exp.get(), PinLabel(*p), GetTheme(ctx_.state->theme).text});
}

std::vector<Command> ComparePanel::Rows() {
  using rows::Initial;
  using rows::Offer;
  using rows::Whole;
  using Src = CommandSource;
  auto panel = [](const AppUi& ui) { return ui.Find<ComparePanel>(); };
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "pin",
       .menu = "Compare/Pin this run",
       .help = "Keep the run as it stands as a reference, drawn faded and dashed",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdPin(); }});
  row({.name = "unpin",
       .args = {Offer(Whole("N", 1, 1000000),
                      [panel](const AppUi& ui) {
                        std::vector<std::string> out;
                        for (const auto& p : panel(ui)->pins()) out.push_back(std::to_string(p->id));
                        return out;
                      })},
       .menu = "Compare/Unpin",
       .help = "Drop pin N",
       .disabled =
           [panel](const AppUi& ui) {
             return panel(ui)->pins().empty() ? std::string("nothing is pinned") : std::string();
           },
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdUnpin(static_cast<int>(a.Whole(0)));
       }});
  row({.name = "unpin-all",
       .menu = "Compare/Unpin all",
       .help = "Drop every pin",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdUnpinAll(); }});
  row({.name = "seeds",
       .args = {Initial(Whole("N", 1, 100000),
                        [panel](const AppUi& ui) { return std::to_string(panel(ui)->mc_seeds_); })},
       .menu = "Compare/Run N seeds…",
       .help = "Run the current settings over seeds 1..N in the background (as formsim sweep)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdSeeds(static_cast<int>(a.Whole(0)));
       }});
  row({.name = "cancel-seeds",
       .menu = "Compare/Cancel the seeds",
       .help = "Stop the Monte Carlo under way",
       .disabled =
           [panel](const AppUi& ui) {
             return panel(ui)->SeedsRunning() ? std::string() : std::string("no Monte Carlo is running");
           },
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdCancelSeeds(); }});
  return t;
}

}  // namespace formsim::app
