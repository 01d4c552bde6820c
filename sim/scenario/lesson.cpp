#include "sim/scenario/lesson.hpp"

namespace formsim::sim {

LessonDef ReadLesson(YamlReader& b) {
  LessonDef l;
  l.present = true;
  auto text = [&](const char* key) {
    const std::string s = b.RequiredString(key);
    if (s.find_first_not_of(" \t\n") == std::string::npos) b.Fail(key, "must not be empty");
    return s;
  };
  l.title = text("title");
  l.goal = text("goal");
  l.watch = text("watch");
  l.try_next = text("try_next");
  l.equations = b.Strings("equations", {});
  for (const std::string& e : l.equations)
    if (e.find_first_not_of(" \t\n") == std::string::npos) b.Fail("equations", "an equation is empty");
  b.Finish();
  return l;
}

}  // namespace formsim::sim
