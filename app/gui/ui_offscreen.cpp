#include "app/gui/ui_offscreen.hpp"

#include "app/gui/ui.hpp"

namespace formsim::app {
namespace {

// An AppUi on the exported session, drawn without input.
class AppUiFrames final : public UiFrames {
 public:
  explicit AppUiFrames(sim::Session& session) : ui_(session) {}
  AppUi& ui() { return ui_; }
  const std::vector<std::uint8_t>& Render(OffscreenRenderer& renderer) override {
    return RenderUi(renderer, ui_);
  }
  void TrackBounds() override { ui_.TrackBounds(); }
  void FitNow() override { ui_.state().fit_now = true; }

 private:
  AppUi ui_;
};

}  // namespace

const std::vector<std::uint8_t>& RenderUi(OffscreenRenderer& renderer, AppUi& ui) {
  const std::vector<std::uint8_t>& pixels = renderer.RenderImGuiFrame(
      [&ui](ImVec2 display, const Fonts& fonts) { ui.Draw(display, fonts, false); });
  ui.AfterRender();  // after the frame's ImGui::Render: the layout report reads its draw data
  return pixels;
}

std::unique_ptr<UiFrames> MakeUiFrames(sim::Session& session, const ExportOptions& opt) {
  auto frames = std::make_unique<AppUiFrames>(session);
  UiState& state = frames->ui().state();
  state.playing = false;
  state.whole_run = opt.whole_run;
  state.theme = opt.theme;
  state.plots_every_frame = true;
  state.overlays = opt.overlays;
  state.legend = opt.legend;
  return frames;
}

}  // namespace formsim::app
