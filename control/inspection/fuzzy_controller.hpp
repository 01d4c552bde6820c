#pragma once
/// \file The paper's two-input, three-output fuzzy controller (section 2), built on fuzzylite
/// from an FLL file the user can edit and reload (assets/fuzzy/inspection.fll).
///
/// Inputs: `s` (lateral offset, m) and `dphi` (heading error, degrees). Outputs: `u1`, `u2`
/// (left / right drive speed levels) and `u3` (steering servo command).
///
/// Inference is Mamdani: each rule's firing strength clips its output terms (the FLL's
/// implication), the clipped sets of all rules are aggregated (the FLL's aggregation) into one
/// output fuzzy set per output, and that set is defuzzified by the paper's weighted average
/// over the universe (section 2): every element x_i of the output's range weighs by its
/// membership u_i, x0 = Σ x_i u_i / Σ u_i. That is fuzzylite's Centroid defuzzifier, whose
/// resolution is the number of elements; the loader refuses any other defuzzifier.

#include <memory>
#include <string>
#include <vector>

namespace fl {
class Engine;
}

namespace formsim::control::inspection {

/// One control decision.
struct FuzzyOutputs {
  double u1 = 0.0;    ///< left drive level
  double u2 = 0.0;    ///< right drive level
  double u3 = 360.0;  ///< steering servo command
  bool ok = false;    ///< false when no rule fired (the outputs are then the safe stop values)
};

/// A membership function sampled for plotting.
struct FuzzyTermCurve {
  std::string name;
  std::vector<double> x, y;
};

/// A linguistic variable with its terms and its current value.
struct FuzzyVariableInfo {
  std::string name;
  bool input = true;
  double min = 0.0, max = 1.0;
  double value = 0.0;
  std::vector<FuzzyTermCurve> terms;
  /// Outputs: the aggregated output fuzzy set of the last Process() on the terms' grid (what
  /// the weighted average defuzzified; all zero when no rule fired).
  FuzzyTermCurve output_set;
};

/// A rule and how strongly it fired in the last Process().
struct FuzzyRuleInfo {
  std::string text;
  std::string s, dphi, u1, u2, u3;  ///< term names when the rule uses that variable
  double strength = 0.0;
};

class FuzzyController {
 public:
  FuzzyController();
  ~FuzzyController();
  FuzzyController(const FuzzyController&) = delete;
  FuzzyController& operator=(const FuzzyController&) = delete;

  /// Loads (or reloads) the engine from an FLL file. On any error, throws std::runtime_error
  /// naming the file and the problem, and the previously loaded engine stays in use.
  void LoadFile(const std::string& path);
  /// Same from FLL text; `origin` names it in messages.
  void LoadText(const std::string& fll, const std::string& origin);
  bool loaded() const { return engine_ != nullptr; }
  const std::string& origin() const { return origin_; }

  /// Evaluates the rule base. `s` in metres, `dphi_deg` in degrees; inputs outside the ranges
  /// are clamped to them. Never returns NaN: when no rule fires, ok = false and the outputs
  /// are the stop command (u1 = u2 = 0, u3 = mid-range).
  FuzzyOutputs Process(double s, double dphi_deg);

  /// Scaling factors of the inputs (the classical normalisation gains of a fuzzy controller):
  /// the universe and every term of `s` (and of `dphi`) stretched by `s_scale` (`dphi_scale`),
  /// so a term that peaks at 0.04 m with s_scale = 1 peaks at 0.08 m with s_scale = 2. It is
  /// exact for every term shape: the engine sees s / s_scale. 1 = the rule base as written;
  /// kept across reloads. Throws std::invalid_argument unless both are finite and > 0.
  void SetInputScales(double s_scale, double dphi_scale);
  double s_scale() const { return scale_[0]; }
  double dphi_scale() const { return scale_[1]; }

  /// The rules with their firing strengths from the last Process().
  const std::vector<FuzzyRuleInfo>& rules() const { return rules_; }
  /// Inputs s, dphi and outputs u1, u2, u3 with their membership functions (the inputs' as
  /// stretched by the input scales, in metres and degrees) and the values of the last Process().
  const std::vector<FuzzyVariableInfo>& variables() const { return variables_; }
  double u3_center() const;

 private:
  void SampleOutputSets();
  void ScaleInputCurves();
  std::unique_ptr<fl::Engine> engine_;
  std::string origin_;
  std::vector<FuzzyRuleInfo> rules_;
  std::vector<FuzzyVariableInfo> variables_;
  std::vector<FuzzyVariableInfo> unscaled_inputs_;  ///< s, dphi as written (scale 1)
  double scale_[2] = {1.0, 1.0};                    ///< s_scale, dphi_scale
};

}  // namespace formsim::control::inspection
