#include "sim/formation/cascade_generator.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace formsim::sim::formation {
namespace {

YAML::Node Flow(std::initializer_list<double> v) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double x : v) n.push_back(x);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

std::string Name(int index) {
  return "R" + std::to_string(index + 1);
}

}  // namespace

YAML::Node MakeCascadeTree(int n_robots, bool ukf, double spacing) {
  if (n_robots < 1) throw std::invalid_argument("MakeCascadeScenario: n_robots must be >= 1");
  const double L = 0.15, d = spacing, h = 0.9186e-4;
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n_robots))));
  YAML::Node root;
  root["type"] = "formation";
  root["name"] = "cascade" + std::to_string(n_robots) + (ukf ? "_ukf" : "");
  root["description"] = "Generated " + std::to_string(n_robots) + "-robot cascade grid" +
                        (ukf ? " with a UKF per link" : "");
  root["seed"] = 1;
  root["dt"] = 0.01;
  root["duration"] = 10.0;
  root["record_every"] = 10;
  root["formation"]["L"] = L;
  root["formation"]["gain_reading"] = "per_sample";
  if (ukf) {
    root["noise"]["phi_variance"] = h;
    root["noise"]["alpha_variance"] = h;
  }
  root["draw"]["trail_length"] = 100;

  // Desired place of grid cell (r, c) in the leader frame (x forward, y left), heading 0.
  auto cell = [&](int r, int c) { return std::pair<double, double>{-r * d, -c * d}; };
  const double heading = 0.3;
  const double ch = std::cos(heading), sh = std::sin(heading);
  for (int k = 0; k < n_robots; ++k) {
    const int r = k / cols, c = k % cols;
    auto [x, y] = cell(r, c);
    // A deterministic displacement of up to ±3 cm and ±0.05 rad.
    const double jx = 0.03 * std::sin(1.7 * k + 0.3), jy = 0.03 * std::cos(2.3 * k + 0.1);
    const double jt = k == 0 ? 0.0 : 0.05 * std::sin(0.9 * k);
    YAML::Node robot;
    robot["name"] = Name(k);
    robot["pose"] =
        Flow({ch * (x + jx) - sh * (y + jy), sh * (x + jx) + ch * (y + jy), heading + jt});
    if (k == 0) {
      robot["schedule"]["kind"] = "line_curve";
      robot["schedule"]["v"] = 2.5;
      robot["schedule"]["omega"] = 0.05;
    } else {
      YAML::Node f;
      if (r == 0 || c == 0) {
        // l-φ to the left neighbour (front line) or to the robot ahead (left column).
        const int leader = r == 0 ? k - 1 : k - cols;
        auto [lx, ly] = r == 0 ? cell(r, c - 1) : cell(r - 1, c);
        const double mx = x + L - lx, my = y - ly;
        f["law"] = "l_phi";
        f["leaders"].push_back(Name(leader));
        f["l_des"] = std::hypot(mx, my);
        f["phi_des"] = std::atan2(my, mx);
      } else {
        // l-l to the robot ahead and the left neighbour.
        auto [ax, ay] = cell(r - 1, c);
        auto [bx, by] = cell(r, c - 1);
        f["law"] = "l_l";
        f["leaders"].push_back(Name(k - cols));
        f["leaders"].push_back(Name(k - 1));
        f["l_des"] = std::hypot(x + L - ax, y - ay);
        f["l2_des"] = std::hypot(x + L - bx, y - by);
        f["k_l2"] = 0.15;
      }
      f["leaders"].SetStyle(YAML::EmitterStyle::Flow);
      f["k_l"] = 0.15;
      if (ukf) f["estimator"] = "ukf";
      robot["follow"] = f;
    }
    root["robots"].push_back(robot);
  }
  return root;
}

}  // namespace formsim::sim::formation

namespace formsim::sim::formation {

std::string MakeCascadeScenario(int n_robots, bool ukf, double spacing) {
  YAML::Emitter out;
  out << MakeCascadeTree(n_robots, ukf, spacing);
  return std::string(out.c_str()) + "\n";
}

}  // namespace formsim::sim::formation
