// Tests of the experiment loop, loader, parameters and outputs with a minimal experiment kind
// defined here: one unicycle with a noisy speed sensor.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/core/experiment.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/unicycle_drive.hpp"

using namespace formsim;
using namespace formsim::sim;

namespace {

class NoisyCircle : public Experiment {
 public:
  NoisyCircle(const ExperimentSetup& s, YamlReader& root) : Experiment(s) {
    v_ = root.Double("v", 1.0);
    omega_ = root.Double("omega", 0.5);
    sigma_ = root.Double("sigma", 0.1);
    YamlReader drive = root.Map("drive");
    RobotDef def = DefaultRobotDef();
    def.name = "R1";
    robot_ = &world_.CreateRobot(def);
    auto d = std::make_unique<UnicycleDrive>(ReadUnicycleDrive(drive));
    drive_ = d.get();
    robot_->SetDrive(std::move(d));
    sensor_ = rng_.Fork(1);
    params_.AddDouble("v", "Gains/R1", "v", &v_, 0, 3, "m/s");
    params_.AddDouble("sigma", "Noise/R1", "σ", &sigma_, 0, 1, "m/s");
    for (const char* c : {"t", "x", "y", "measured_v"}) recorder_.AddColumn(c);
    Start();
  }
  std::vector<FigureSpec> Figures() const override { return {}; }
  Json Summary() const override {
    Json j = Json::Object();
    j["x"] = robot_->pose().x;
    return j;
  }
  std::string SummaryTable() const override { return "ok\n"; }
  double v() const { return v_; }

 protected:
  void Control(double) override { drive_->SetCommand(v_, omega_); }
  void Sense(double) override { measured_ = robot_->forward_speed() + sensor_.Normal(0, sigma_); }
  void Record(Recorder& rec) override {
    rec.Set(0, time());
    rec.Set(1, robot_->pose().x);
    rec.Set(2, robot_->pose().y);
    rec.Set(3, measured_);
  }
  void DrawScene(DrawSink&) const override {}

 private:
  Robot* robot_ = nullptr;
  UnicycleDrive* drive_ = nullptr;
  Rng sensor_;
  double v_ = 1, omega_ = 0.5, sigma_ = 0.1, measured_ = 0;
};
FORMSIM_REGISTER_EXPERIMENT("test_noisy_circle", NoisyCircle);

const char* kScenario =
    "type: test_noisy_circle\nname: circle\nseed: 3\ndt: 0.01\nduration: 1.0\n"
    "v: 1.2\nomega: 0.5\nsigma: 0.1\ndrive: {mode: ideal}\n";

std::string Csv(Experiment& e) {
  while (!e.finished()) e.Step();
  const std::string f = std::string(FORMSIM_BINARY_DIR) + "/noisy_circle.csv";
  e.recorder().WriteCsv(f);
  std::ifstream in(f);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string LoadError(const std::string& yaml) {
  try {
    LoadExperimentFromNode(YAML::Load(yaml), "x.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Experiment, SameSeedGivesIdenticalCsvAndOtherSeedDiffers) {
  auto a = LoadExperimentFromNode(YAML::Load(kScenario), "a.yaml");
  auto b = LoadExperimentFromNode(YAML::Load(kScenario), "a.yaml");
  auto c = LoadExperimentFromNode(YAML::Load(kScenario), "a.yaml", 4);
  const std::string ca = Csv(*a), cb = Csv(*b), cc = Csv(*c);
  EXPECT_EQ(ca, cb);
  EXPECT_NE(ca, cc);
  EXPECT_EQ(a->recorder().rows(), 101u) << "row 0 plus one per step";
  EXPECT_EQ(a->steps(), 100);
  EXPECT_DOUBLE_EQ(a->time(), 1.0);
}

TEST(Experiment, LoaderRejectsBadRootsWithKeyAndLine) {
  EXPECT_NE(LoadError("type: nope\n").find("unknown experiment type 'nope'"), std::string::npos);
  EXPECT_NE(LoadError(std::string(kScenario) + "vv: 1\n").find("key 'vv': unknown key"),
            std::string::npos);
  const std::string flying = "type: test_noisy_circle\ndrive: {mode: flying}\n";
  EXPECT_NE(LoadError(flying).find("x.yaml:2:"), std::string::npos) << LoadError(flying);
  EXPECT_NE(LoadError(flying).find("key 'drive.mode'"), std::string::npos) << LoadError(flying);
  const std::string bad_dt = "type: test_noisy_circle\ndt: -1\n";
  EXPECT_NE(LoadError(bad_dt).find("x.yaml:2:"), std::string::npos) << LoadError(bad_dt);
  EXPECT_NE(LoadError("type: test_noisy_circle\nv: .nan\n").find("finite"), std::string::npos);
}

TEST(Experiment, PendingEditsApplyBetweenStepsAndBadValuesAreRejected) {
  auto e = LoadExperimentFromNode(YAML::Load(kScenario), "a.yaml");
  auto* nc = static_cast<NoisyCircle*>(e.get());
  PendingChanges pc;
  pc.edits.push_back({"v", "2.0"});
  pc.edits.push_back({"sigma", "nan"});
  pc.edits.push_back({"nope", "1"});
  const auto errors = e->Apply(pc);
  EXPECT_DOUBLE_EQ(nc->v(), 2.0);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("finite"), std::string::npos);
  EXPECT_NE(errors[1].find("unknown parameter 'nope'"), std::string::npos);
}

TEST(RunOutput, WritesFilesAndRejectsUnwritableFolder) {
  auto e = LoadExperimentFromNode(YAML::Load(kScenario), "a.yaml");
  while (!e->finished()) e->Step();
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/run_output_test";
  WriteRunOutputs(*e, dir);
  EXPECT_TRUE(std::filesystem::exists(dir + "/timeseries.csv"));
  std::ifstream in(dir + "/summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("\"scenario\": \"circle\""), std::string::npos) << ss.str();
  EXPECT_THROW(PrepareOutputDir("/proc/formsim_cannot_write_here"), std::runtime_error);
}
