#include "app/cli/lessons_cli.hpp"

#include <cstdio>
#include <map>
#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/core/task_pool.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/lesson_checks.hpp"
#include "sim/study/sweep_spec.hpp"

namespace formsim::app {
namespace {

// "N checks, H hold, F fail": how `lessons check` and `lessons show` begin their last line.
std::string LessonTally(int checks, int hold, int fail) {
  return sim::Sprintf("%d checks, %d hold, %d fail", checks, hold, fail);
}

}  // namespace

LessonsCommand::LessonsCommand(CLI::App& app) {
  cmd_ = app.add_subcommand("lessons", "Lessons: check that every effect a lesson states happens");
  cmd_->require_subcommand(1);
  check_ = cmd_->add_subcommand(
      "check", "Run every check of every lesson (or those named); exit 1 when one fails");
  check_->add_option("names", names_, "Lesson names or files (default: every shipped lesson)");
  check_->add_option("--seeds", seeds_,
                     "Seeds every check runs on: 1..5, 1,2,5 or a mixture (default: each "
                     "check's own, at least 1..5)");
  check_->add_option("--jobs,-j", jobs_, "Runs at once (default: one per core)")
      ->check(CLI::Range(1, 1024));
  check_->add_option("--set", sets_,
                     "PATH=VALUE applied to every run before each check's own edits (a deliberate "
                     "error some check must catch); repeatable");
  show_ = cmd_->add_subcommand(
      "show", "Print a lesson's text with every check replaced by the value measured on one seed");
  show_->add_option("name", show_name_, "The lesson's name or file")->required();
  show_->add_option("--seed", show_seed_, "The seed its checks run on (default: 1)");
  show_->add_option("--jobs,-j", jobs_, "Runs at once (default: one per core)")
      ->check(CLI::Range(1, 1024));
}

int LessonsCommand::RunShow() {
  sim::LessonCheckOptions opt;
  // One seed, 0 ... 2^64-1, refused by name when out of range or not one (never wrapped).
  opt.seeds = sim::ParseSeeds(show_seed_, "--seed");
  if (opt.seeds.size() != 1)
    throw std::runtime_error("--seed '" + show_seed_ + "': expected one seed, 0 ... 2^64-1");
  opt.jobs = jobs_ > 0 ? jobs_ : sim::TaskPool::HardwareThreads();
  const std::string file = sim::ResolveLesson(show_name_);
  const auto results = sim::CheckLesson(file, opt);
  std::map<std::string, sim::ShownCheck> shown;
  int failed = 0;
  for (const auto& r : results) {
    sim::ShownCheck s;
    s.measured = r.error.empty() && !r.values.empty();
    if (s.measured) s.value = r.values.front();
    if (!r.deciders.empty()) s.robot = r.deciders.front();
    s.holds = r.ok();
    s.some_seeds = r.share < 1;
    shown[r.id] = s;
    // A check that claims a share of the seeds may miss this one; the others must hold.
    if (!r.ok() && !s.some_seeds) ++failed;
  }
  const sim::ParsedScenario parsed = sim::ParseScenario(sim::ScenarioSource::FromFile(file), {});
  const std::string text = sim::RenderLessonText(parsed.lesson, [&](const std::string& id) {
    const auto it = shown.find(id);
    return it == shown.end() ? sim::ShownCheck{} : it->second;
  });
  sim::Print(stdout, "%s\nChecks on seed %llu:\n", text.c_str(),
             static_cast<unsigned long long>(opt.seeds.front()));
  for (const auto& r : results)
    std::fputs(("  " + sim::FormatCheckResult(r) + "\n").c_str(), stdout);
  int missed = 0;
  for (const auto& r : results) missed += !r.ok() && r.share < 1;
  const int checks = static_cast<int>(results.size());
  std::string tally = LessonTally(checks, checks - failed - missed, failed);
  if (missed)
    sim::AppendSprintf(tally, ", %d miss this seed (each claims a share of the seeds only)",
                       missed);
  std::fputs((tally + "\n").c_str(), stdout);
  return failed ? 1 : 0;
}

int LessonsCommand::Run() {
  if (show_->parsed()) return RunShow();
  sim::LessonCheckOptions opt;
  if (!seeds_.empty()) opt.seeds = sim::ParseSeeds(seeds_);
  opt.jobs = jobs_ > 0 ? jobs_ : sim::TaskPool::HardwareThreads();
  opt.extra_sets = sets_;
  std::vector<std::string> files;
  if (names_.empty()) files = sim::ShippedLessons();
  for (const std::string& n : names_) files.push_back(sim::ResolveLesson(n));
  // A --set that a lesson cannot take (an unknown key, a value out of range) is bad input, named
  // and refused before anything runs, not a check that fails on every seed.
  if (!sets_.empty())
    for (const std::string& f : files)
      sim::ParseScenario(sim::ScenarioSource::FromFile(f), sim::CliOverrides(sets_, -1));
  int checks = 0, failed = 0, warned = 0;
  for (const std::string& f : files) {
    const auto results = sim::CheckLesson(f, opt);
    if (results.empty()) std::fputs((f + ": no checks\n").c_str(), stdout);
    for (const auto& r : results) {
      std::fputs((sim::FormatCheckResult(r) + "\n").c_str(), stdout);
      std::fflush(stdout);
      ++checks;
      if (!r.ok()) ++failed;
    }
    // A check the text says depends on the seed, with the same value on every seed checked.
    const sim::ParsedScenario parsed = sim::ParseScenario(sim::ScenarioSource::FromFile(f), {});
    for (const auto& w : sim::SeedEffectWarnings(parsed.lesson, results)) {
      std::fputs((sim::FormatSeedEffectWarning(w) + "\n").c_str(), stdout);
      ++warned;
    }
  }
  std::string tally = LessonTally(checks, checks - failed, failed);
  if (warned)
    sim::AppendSprintf(tally, ", %d claim a seed effect their values do not show", warned);
  std::fputs((tally + "\n").c_str(), stdout);
  return failed || warned ? 1 : 0;
}

}  // namespace formsim::app
