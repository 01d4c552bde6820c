#include <gtest/gtest.h>

#include "sim/core/yaml_reader.hpp"

using formsim::sim::ApplySet;
using formsim::sim::ScenarioError;
using formsim::sim::YamlReader;

namespace {

std::string ScenarioErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(YamlReader, ReadsValuesWithDefaults) {
  YamlReader r(YAML::Load("a: 1.5\nb: 3\nc: true\nname: x\npose: [1, 2, 0.5]\n"), "f.yaml");
  EXPECT_DOUBLE_EQ(r.Double("a", 0), 1.5);
  EXPECT_EQ(r.Int("b", 0), 3);
  EXPECT_TRUE(r.Bool("c", false));
  EXPECT_EQ(r.String("name", ""), "x");
  EXPECT_DOUBLE_EQ(r.Pose("pose", {}).theta, 0.5);
  EXPECT_DOUBLE_EQ(r.Double("missing", 7.0), 7.0);
  EXPECT_NO_THROW(r.Finish());
}

TEST(YamlReader, UnknownKeyNamesFileLineAndKey) {
  const std::string err = ScenarioErrorOf([] {
    YamlReader r(YAML::Load("robot:\n  gain: 1\n  gian: 2\n"), "s.yaml");
    YamlReader robot = r.Map("robot");
    robot.Double("gain", 0);
    robot.Finish();
  });
  EXPECT_NE(err.find("s.yaml:3:"), std::string::npos) << err;
  EXPECT_NE(err.find("robot.gian"), std::string::npos) << err;
  EXPECT_NE(err.find("unknown key"), std::string::npos) << err;
  EXPECT_NE(err.find("gain"), std::string::npos) << "lists allowed keys: " << err;
}

TEST(YamlReader, RejectsNonFiniteAndWrongTypes) {
  EXPECT_NE(
      ScenarioErrorOf([] { YamlReader(YAML::Load("k: .nan"), "f").Double("k", 0); }).find("finite"),
      std::string::npos);
  EXPECT_NE(
      ScenarioErrorOf([] { YamlReader(YAML::Load("k: .inf"), "f").Double("k", 0); }).find("finite"),
      std::string::npos);
  EXPECT_NE(
      ScenarioErrorOf([] { YamlReader(YAML::Load("k: abc"), "f").Double("k", 0); }).find("number"),
      std::string::npos);
  EXPECT_NE(
      ScenarioErrorOf([] { YamlReader(YAML::Load("k: 1.5"), "f").Int("k", 0); }).find("integer"),
      std::string::npos);
  EXPECT_NE(ScenarioErrorOf([] {
              YamlReader(YAML::Load("k: [1, 2]"), "f").Doubles("k", {}, 3);
            }).find("expected 3 numbers"),
            std::string::npos);
  EXPECT_NE(ScenarioErrorOf([] {
              YamlReader(YAML::Load("k: maybe"), "f").Choice("k", {"a", "b"}, 0);
            }).find("not one of: a, b"),
            std::string::npos);
}

TEST(YamlReader, SetAddressesListItemsByNameAndIndex) {
  YAML::Node root = YAML::Load("robots:\n  - {name: R1, k: 1}\n  - {name: R2, k: 2}\ndt: 0.01\n");
  EXPECT_EQ(ApplySet(root, "robots.R2.k=5"), "");
  EXPECT_EQ(ApplySet(root, "robots.0.k=4"), "");
  EXPECT_EQ(ApplySet(root, "dt=0.02"), "");
  EXPECT_EQ(ApplySet(root, "robots.R1.pose=[1, 2, 3]"), "");
  EXPECT_EQ(root["robots"][1]["k"].as<double>(), 5.0);
  EXPECT_EQ(root["robots"][0]["k"].as<double>(), 4.0);
  EXPECT_EQ(root["robots"][0]["pose"].size(), 3u);
  EXPECT_EQ(root["dt"].as<double>(), 0.02);
  EXPECT_NE(ApplySet(root, "robots.R9.k=1").find("no list item named 'R9'"), std::string::npos);
  EXPECT_NE(ApplySet(root, "novalue").find("path.to.key=value"), std::string::npos);
}

TEST(YamlReader, SyntaxErrorHasLine) {
  const std::string path = std::string(FORMSIM_BINARY_DIR) + "/bad_syntax.yaml";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("a: 1\nb: [1, 2\nc: 3\n", f);
    std::fclose(f);
  }
  const std::string err = ScenarioErrorOf([&] { formsim::sim::LoadYamlFile(path); });
  EXPECT_NE(err.find("bad_syntax.yaml:"), std::string::npos) << err;
  EXPECT_NE(err.find("syntax"), std::string::npos) << err;
}
