#include "app/cli/lessons_cli.hpp"

#include <cstdio>
#include <stdexcept>

#include "sim/core/task_pool.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/study/lesson_checks.hpp"
#include "sim/study/sweep_spec.hpp"

namespace formsim::app {

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
}

int LessonsCommand::Run() {
  sim::LessonCheckOptions opt;
  if (!seeds_.empty()) opt.seeds = sim::ParseSeeds(seeds_);
  opt.jobs = jobs_ > 0 ? jobs_ : sim::TaskPool::HardwareThreads();
  std::vector<std::string> files;
  if (names_.empty()) files = sim::ShippedLessons();
  for (const std::string& n : names_) files.push_back(sim::ResolveLesson(n));
  int checks = 0, failed = 0;
  for (const std::string& f : files) {
    const auto results = sim::CheckLesson(f, opt);
    if (results.empty()) std::printf("%s: no checks\n", f.c_str());
    for (const auto& r : results) {
      std::printf("%s\n", sim::FormatCheckResult(r).c_str());
      std::fflush(stdout);
      ++checks;
      if (!r.ok()) ++failed;
    }
  }
  std::printf("%d checks, %d hold, %d fail\n", checks, checks - failed, failed);
  return failed ? 1 : 0;
}

}  // namespace formsim::app
