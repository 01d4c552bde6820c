// libFuzzer harness for lesson files (a scenario with a `lesson:` block, assets/lessons/): any
// bytes read through the one load path (ParseScenario reads the block strictly), and the
// `lesson:` block alone through ReadLesson, so that mutations of the block are read even when
// the scenario around them no longer loads. Errors must be messages, never crashes.
// Seeds: tests/fuzz/lesson_seeds (the shipped lessons).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "sim/scenario/lesson.hpp"
#include "sim/scenario/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace formsim::sim;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ParsedScenario parsed =
        ParseScenario(ScenarioSource::FromText(text, "fuzz_lesson.yaml",
                                               std::string(FORMSIM_SOURCE_DIR) + "/assets/lessons"),
                      {});
    // What the Lesson panel shows, without drawing it.
    std::size_t shown = parsed.lesson.title.size() + parsed.lesson.goal.size();
    for (const LessonStep& s : parsed.lesson.steps) {
      shown += s.text.size() + s.action.label.size() + s.predict.question.size();
      for (const std::string& o : s.predict.options) shown += o.size();
      for (const std::string& id : s.Checks()) shown += parsed.lesson.Find(id) != nullptr;
    }
    for (const std::string& e : parsed.lesson.equations) shown += e.size();
    (void)shown;
  } catch (const std::exception&) {
  }
  try {
    const YAML::Node root = LoadYamlText(text, "fuzz_lesson.yaml");
    if (root.IsMap() && root["lesson"]) {
      YamlReader block(root["lesson"], "fuzz_lesson.yaml", "lesson");
      (void)ReadLesson(block);
    }
  } catch (const std::exception&) {
  }
  return 0;
}
