// Cost of one exported figure in each format (issue 16): the same plot (the paper's Fig. 3 (a),
// three trajectories, 960x600) and the same world view (1280x720) drawn as a PNG (OSMesa
// rasterisation, read-back and zlib encoding), and recorded and written as SVG and as PDF
// (Cairo, fonts subset and embedded). Files go to a temporary folder.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/export/png_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "app/render/world_view.hpp"
#include "sim/session/session.hpp"

using namespace formsim;
using namespace formsim::app;

namespace {

// The paper run, simulated once.
sim::Session& PaperRun() {
  static sim::Session* s = [] {
    auto* session = new sim::Session(
        std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/formation_traj2_ukf.yaml",
        std::vector<sim::Override>{});
    while (!session->exp().finished()) session->Step();
    return session;
  }();
  return *s;
}

PlotData Trajectories() {
  for (const auto& f : PaperRun().exp().Figures())
    if (f.id == "trajectories") return ResolveFigure(f, PaperRun().exp().recorder());
  return {};
}

std::string Dir() {
  const auto d = std::filesystem::temp_directory_path() / "formsim_bench_figures";
  std::filesystem::create_directories(d);
  return d.string();
}

void BM_FigurePng(benchmark::State& state) {
  const PlotData data = Trajectories();
  OffscreenRenderer r(960, 600);
  const std::string path = Dir() + "/f.png";
  for (auto _ : state) {
    const auto& px = r.RenderFigure(data, 960, 600);
    WritePng(path, r.width(), r.height(), px.data());
  }
}
BENCHMARK(BM_FigurePng)->Unit(benchmark::kMillisecond);

void BM_FigureVector(benchmark::State& state, FigureFormat format) {
  const PlotData data = Trajectories();
  const FigureSize size = ParseFigureSize("960x600", "--plot-size");
  const std::string path = Dir() + "/f." + FormatExtension(format);
  for (auto _ : state)
    WriteVectorFigure(RecordPlot(data, 960, 600, GetTheme(ThemeId::kLight)), format, size,
                      data.title, path);
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
}
BENCHMARK_CAPTURE(BM_FigureVector, svg, FigureFormat::kSvg)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FigureVector, pdf, FigureFormat::kPdf)->Unit(benchmark::kMillisecond);

void BM_WorldVector(benchmark::State& state, FigureFormat format) {
  View view;
  AutoFit fit;
  FrameWorldView(PaperRun().exp(), 1280, 720, view, fit, true);
  const FigureSize size = ParseFigureSize("1280x720", "--snapshot");
  const std::string path = Dir() + "/w." + FormatExtension(format);
  for (auto _ : state)
    WriteVectorFigure(RecordWorld(PaperRun().exp(), view, GetTheme(ThemeId::kLight), "bench"),
                      format, size, "bench", path);
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
}
BENCHMARK_CAPTURE(BM_WorldVector, svg, FigureFormat::kSvg)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WorldVector, pdf, FigureFormat::kPdf)->Unit(benchmark::kMillisecond);

void BM_WorldPng(benchmark::State& state) {
  OffscreenRenderer r(1280, 720);
  View view;
  AutoFit fit;
  const std::string path = Dir() + "/w.png";
  for (auto _ : state) {
    const auto& px = r.RenderWorld(PaperRun().exp(), view, fit, true, "bench");
    WritePng(path, r.width(), r.height(), px.data());
  }
}
BENCHMARK(BM_WorldPng)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
