#include "control/inspection/fuzzy_controller.hpp"

#include <fl/Headers.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace formsim::control::inspection {
namespace {

const char* const kInputs[] = {"s", "dphi"};
const char* const kOutputs[] = {"u1", "u2", "u3"};
constexpr int kCurveSamples = 241;

[[noreturn]] void Fail(const std::string& origin, const std::string& message) {
  throw std::runtime_error(origin + ": fuzzy rule base: " + message);
}

// Break points of the piecewise-linear shapes, so plotted peaks and corners are exact.
void AddVertices(const fl::Term* t, std::vector<double>* xs) {
  if (const auto* tri = dynamic_cast<const fl::Triangle*>(t)) {
    xs->insert(xs->end(), {tri->getVertexA(), tri->getVertexB(), tri->getVertexC()});
  } else if (const auto* tr = dynamic_cast<const fl::Trapezoid*>(t)) {
    xs->insert(xs->end(), {tr->getVertexA(), tr->getVertexB(), tr->getVertexC(), tr->getVertexD()});
  } else if (const auto* r = dynamic_cast<const fl::Ramp*>(t)) {
    xs->insert(xs->end(), {r->getStart(), r->getEnd()});
  } else if (const auto* rect = dynamic_cast<const fl::Rectangle*>(t)) {
    xs->insert(xs->end(), {rect->getStart(), rect->getEnd()});
  }
}

// Samples every term of a variable on one grid: uniform plus all the terms' break points.
std::vector<FuzzyTermCurve> SampleTerms(const std::vector<fl::Term*>& terms, double lo, double hi) {
  std::vector<double> xs;
  for (int i = 0; i < kCurveSamples; ++i) xs.push_back(lo + (hi - lo) * i / (kCurveSamples - 1));
  for (const fl::Term* t : terms) AddVertices(t, &xs);
  xs.erase(std::remove_if(xs.begin(), xs.end(), [&](double x) { return !(x >= lo && x <= hi); }),
           xs.end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::vector<FuzzyTermCurve> out;
  for (const fl::Term* t : terms) {
    FuzzyTermCurve c;
    c.name = t->getName();
    c.x = xs;
    for (double x : xs) c.y.push_back(t->membership(x));
    out.push_back(c);
  }
  return out;
}

// The term named after "<variable> is" in a rule's text (hedges such as "very" are skipped).
std::string TermOf(const std::string& text, const std::string& variable) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  static const char* const kHedges[] = {"not", "very", "somewhat", "seldom", "extremely", "any"};
  for (std::size_t i = 0; i + 2 < words.size(); ++i) {
    if (words[i] != variable || words[i + 1] != "is") continue;
    std::size_t k = i + 2;
    while (k < words.size() &&
           std::find(std::begin(kHedges), std::end(kHedges), words[k]) != std::end(kHedges))
      ++k;
    return k < words.size() ? words[k] : std::string();
  }
  return std::string();
}

}  // namespace

FuzzyController::FuzzyController() = default;
FuzzyController::~FuzzyController() = default;

void FuzzyController::LoadFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) Fail(path, "cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  LoadText(ss.str(), path);
}

void FuzzyController::LoadText(const std::string& fll, const std::string& origin) {
  fl::fuzzylite::setLogging(false);
  std::unique_ptr<fl::Engine> engine;
  try {
    engine.reset(fl::FllImporter().fromString(fll));
  } catch (const std::exception& e) {
    Fail(origin, std::string("FLL syntax: ") + e.what());
  }
  for (const char* name : kInputs)
    if (!engine->hasInputVariable(name))
      Fail(origin, std::string("missing input variable '") + name + "'");
  for (const char* name : kOutputs)
    if (!engine->hasOutputVariable(name))
      Fail(origin, std::string("missing output variable '") + name + "'");
  if (engine->numberOfInputVariables() != 2 || engine->numberOfOutputVariables() != 3)
    Fail(origin, "expected exactly the inputs s, dphi and the outputs u1, u2, u3");
  if (engine->numberOfRuleBlocks() < 1 || engine->getRuleBlock(0)->numberOfRules() == 0)
    Fail(origin, "no rules");

  std::vector<FuzzyVariableInfo> vars;
  for (const char* name : kInputs) {
    fl::InputVariable* v = engine->getInputVariable(name);
    if (v->numberOfTerms() == 0) Fail(origin, std::string("input '") + name + "' has no terms");
    FuzzyVariableInfo info;
    info.name = name;
    info.input = true;
    info.min = v->getMinimum();
    info.max = v->getMaximum();
    info.terms = SampleTerms(v->terms(), info.min, info.max);
    vars.push_back(info);
  }
  // Outputs: the paper's weighted average over the universe is fuzzylite's Centroid.
  for (const char* name : kOutputs) {
    fl::OutputVariable* v = engine->getOutputVariable(name);
    if (v->numberOfTerms() == 0) Fail(origin, std::string("output '") + name + "' has no terms");
    if (!dynamic_cast<fl::Centroid*>(v->getDefuzzifier()))
      Fail(origin, std::string("output '") + name +
                       "': defuzzifier must be Centroid (the paper's weighted average over the "
                       "universe, section 2)");
    if (!v->fuzzyOutput()->getAggregation())
      Fail(origin, std::string("output '") + name + "': an aggregation operator is needed");
    FuzzyVariableInfo info;
    info.name = name;
    info.input = false;
    info.min = v->getMinimum();
    info.max = v->getMaximum();
    info.terms = SampleTerms(v->terms(), info.min, info.max);
    info.output_set.name = "output set";
    info.output_set.x = info.terms.front().x;
    info.output_set.y.assign(info.output_set.x.size(), 0.0);
    vars.push_back(info);
  }
  // (Re)load every rule; a rule naming an unknown variable or term is an error that quotes the
  // rule.
  std::vector<FuzzyRuleInfo> rules;
  for (std::size_t b = 0; b < engine->numberOfRuleBlocks(); ++b) {
    fl::RuleBlock* block = engine->getRuleBlock(b);
    block->unloadRules();
    for (fl::Rule* r : block->rules()) {
      try {
        r->load(engine.get());
      } catch (const std::exception& e) {
        std::string why = e.what();
        why = why.substr(0, why.find('\n'));
        Fail(origin, "cannot load rule '" + r->getText() + "': " + why);
      }
      FuzzyRuleInfo info;
      info.text = r->getText();
      info.s = TermOf(info.text, "s");
      info.dphi = TermOf(info.text, "dphi");
      info.u1 = TermOf(info.text, "u1");
      info.u2 = TermOf(info.text, "u2");
      info.u3 = TermOf(info.text, "u3");
      rules.push_back(info);
    }
  }
  std::string status;
  if (!engine->isReady(&status)) Fail(origin, "engine not ready: " + status);

  engine_ = std::move(engine);
  origin_ = origin;
  rules_ = std::move(rules);
  variables_ = std::move(vars);
  unscaled_inputs_.assign(variables_.begin(), variables_.begin() + 2);
  ScaleInputCurves();
}

void FuzzyController::SetInputScales(double s_scale, double dphi_scale) {
  if (!(std::isfinite(s_scale) && s_scale > 0.0) ||
      !(std::isfinite(dphi_scale) && dphi_scale > 0.0))
    throw std::invalid_argument("fuzzy input scales must be finite and > 0");
  scale_[0] = s_scale;
  scale_[1] = dphi_scale;
  ScaleInputCurves();
}

// The inputs' curves and ranges in the controller's units: the terms as written, stretched.
void FuzzyController::ScaleInputCurves() {
  for (std::size_t i = 0; i < unscaled_inputs_.size() && i < variables_.size(); ++i) {
    const FuzzyVariableInfo& base = unscaled_inputs_[i];
    FuzzyVariableInfo& v = variables_[i];
    const double k = scale_[i];
    v.min = base.min * k;
    v.max = base.max * k;
    for (std::size_t t = 0; t < v.terms.size(); ++t)
      for (std::size_t j = 0; j < v.terms[t].x.size(); ++j)
        v.terms[t].x[j] = base.terms[t].x[j] * k;
  }
}

void FuzzyController::SampleOutputSets() {
  for (auto& v : variables_) {
    if (v.input) continue;
    const fl::Aggregated* set = engine_->getOutputVariable(v.name)->fuzzyOutput();
    for (std::size_t i = 0; i < v.output_set.x.size(); ++i)
      v.output_set.y[i] = set->membership(v.output_set.x[i]);
  }
}

double FuzzyController::u3_center() const {
  for (const auto& v : variables_)
    if (v.name == "u3") return 0.5 * (v.min + v.max);
  return 360.0;
}

FuzzyOutputs FuzzyController::Process(double s, double dphi_deg) {
  FuzzyOutputs out;
  out.u3 = u3_center();
  if (!engine_) return out;
  fl::InputVariable* in_s = engine_->getInputVariable("s");
  fl::InputVariable* in_d = engine_->getInputVariable("dphi");
  // Clamp (and replace a non-finite input by the range centre, which then fires no error).
  auto clamp_in = [](fl::InputVariable* v, double x) {
    if (!std::isfinite(x)) return 0.5 * (v->getMinimum() + v->getMaximum());
    return std::clamp(x, v->getMinimum(), v->getMaximum());
  };
  // The scales stretch the terms: a term evaluated at s / k is the term stretched by k at s.
  in_s->setValue(clamp_in(in_s, s / scale_[0]));
  in_d->setValue(clamp_in(in_d, dphi_deg / scale_[1]));
  engine_->process();
  const double u1 = engine_->getOutputVariable("u1")->getValue();
  const double u2 = engine_->getOutputVariable("u2")->getValue();
  const double u3 = engine_->getOutputVariable("u3")->getValue();

  std::size_t k = 0;
  for (std::size_t b = 0; b < engine_->numberOfRuleBlocks(); ++b)
    for (const fl::Rule* r : engine_->getRuleBlock(b)->rules())
      if (k < rules_.size()) rules_[k++].strength = r->getActivationDegree();
  for (auto& v : variables_) {
    if (v.name == "s") v.value = in_s->getValue() * scale_[0];
    if (v.name == "dphi") v.value = in_d->getValue() * scale_[1];
  }
  if (!std::isfinite(u1) || !std::isfinite(u2) || !std::isfinite(u3)) {
    out.ok = false;  // no rule fired: stop and go straight
    for (auto& v : variables_) {
      if (v.name == "u1" || v.name == "u2") v.value = 0.0;
      if (v.name == "u3") v.value = out.u3;
    }
    SampleOutputSets();
    return out;
  }
  out.ok = true;
  out.u1 = u1;
  out.u2 = u2;
  out.u3 = u3;
  for (auto& v : variables_) {
    if (v.name == "u1") v.value = u1;
    if (v.name == "u2") v.value = u2;
    if (v.name == "u3") v.value = u3;
  }
  SampleOutputSets();
  return out;
}

}  // namespace formsim::control::inspection
