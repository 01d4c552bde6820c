#include "app/gui/command_row_makers.hpp"

#include "app/gui/ui.hpp"

namespace formsim::app::rows {

CommandArg Whole(std::string name, double lo, double hi, std::string unit) {
  CommandArg a;
  a.name = std::move(name);
  a.type = ArgType::kWhole;
  a.lo = lo;
  a.hi = hi;
  a.unit = std::move(unit);
  return a;
}

CommandArg Real(std::string name, double lo, double hi, std::string unit) {
  CommandArg a = Whole(std::move(name), lo, hi, std::move(unit));
  a.type = ArgType::kReal;
  return a;
}

CommandArg Text(std::string name, std::string what, ArgType type) {
  CommandArg a;
  a.name = std::move(name);
  a.type = type;
  a.what = std::move(what);
  return a;
}

CommandArg OnOff() {
  CommandArg a;
  a.name = "STATE";
  a.type = ArgType::kOnOff;
  return a;
}

CommandArg Choice(std::string name, std::vector<std::string> choices) {
  CommandArg a;
  a.name = std::move(name);
  a.type = ArgType::kChoice;
  a.choices = std::move(choices);
  return a;
}

CommandArg Optional(CommandArg a) {
  a.optional = true;
  return a;
}

CommandArg Offer(CommandArg a, std::function<std::vector<std::string>(const AppUi&)> offer) {
  a.offer = std::move(offer);
  return a;
}

CommandArg Initial(CommandArg a, std::function<std::string(const AppUi&)> initial) {
  a.initial = std::move(initial);
  return a;
}

std::vector<std::string> RobotNames(const AppUi& ui) {
  std::vector<std::string> out = {"nobody"};
  for (const auto& r : ui.session().exp().world().robots()) out.push_back(r->name());
  return out;
}

}  // namespace formsim::app::rows
