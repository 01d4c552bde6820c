// The window's command table (app/gui/command_table.hpp) and everything generated from it: each
// command is reachable three ways (a click on its menu item, the palette, `--script`), runs in
// a window (an OSMesa context, in-process; under ASan in the sanitizer suite), refuses bad
// arguments naming the argument; keys, F1 help and docs/window.md's table come from the same rows.
#include "app/gui/parameters_panel.hpp"
#include "app/gui/command_table.hpp"

#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/gui/ui.hpp"
#include "tests/app/test_util.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

// Large enough for every menu to open in full.
class TableWindow : public testing::UiWindow {
 public:
  explicit TableWindow(const std::string& scenario = "formation_switching")
      : UiWindow(scenario, 1600, 900) {}
};

std::string TopOf(const std::string& menu) {
  return menu.substr(0, menu.find('/'));
}

// Arguments a command accepts in formation_switching (free-text arguments need real values).
std::string GoodArgs(const Command& c, AppUi& ui, const std::string& dir) {
  static const std::map<std::string, std::string> kFree = {
      {"open", ""},  // filled below: a file that exists
      {"load", "formation_traj2"},
      {"save", ""},
      {"save-as", ""},
      {"save-session", ""},
      {"screenshot", ""},
      {"export-figures", ""},
      {"reset-seed", "7"},
      {"edit", "robots.R2.follow.k_l=0.3"},
      {"revert", "robots.R2.follow.k_l"},
      {"overlay", "all"},
      {"formation", "remove R7"},
      {"scrub", "0"},
      {"slot", "R2 0.2 -0.4"},
      {"switch-formation", ""},
      {"palette", "k_l R2"},
      {"action", "switch-formation"},
      {"field-open", "robots.R2.follow.k_l"},
      {"field-type", "0.3"},
      {"field-wheel", "robots.R2.follow.k_l 1"},
  };
  if (c.name == "open") return testing::Scenario("formation_traj2");
  if (c.name == "save" || c.name == "save-as") return dir + "/" + c.name + ".yaml";
  if (c.name == "save-session") return dir + "/session.yaml";
  if (c.name == "screenshot") return dir + "/shot.png";
  if (c.name == "export-figures") return dir + "/figures";
  if (c.name == "layout-report") return dir + "/layout.json";
  if (const auto f = kFree.find(c.name); f != kFree.end()) return f->second;
  std::string args;
  for (const CommandArg& a : c.args) {
    if (a.optional) break;
    std::string v;
    if (a.type == ArgType::kWhole || a.type == ArgType::kReal)
      v = "1";
    else if (a.type == ArgType::kOnOff)
      v = "on";
    else if (a.initial)
      v = a.initial(ui);
    else if (!a.choices.empty())
      v = a.choices.front();
    else if (a.offer && !a.offer(ui).empty())
      v = a.offer(ui).back();
    args += (args.empty() ? "" : " ") + v;
  }
  return args;
}

TEST(CommandTable, RowsAreWellFormed) {
  std::set<std::string> names, keys;
  const std::set<std::string> menus = {"File", "Run", "View", "Compare", "Formation", "Help"};
  for (const Command& c : Commands()) {
    EXPECT_TRUE(names.insert(c.name).second) << "two rows named " << c.name;
    EXPECT_FALSE(c.help.empty()) << c.name;
    EXPECT_TRUE(c.run) << c.name;
    for (const std::string& k : c.keys)
      EXPECT_TRUE(keys.insert(k).second) << "key " << k << " bound twice";
    if (!c.script_only) {
      EXPECT_EQ(menus.count(TopOf(c.menu)), 1u) << c.name << ": " << c.menu;
    }
    bool optional = false;
    for (std::size_t i = 0; i < c.args.size(); ++i) {
      const CommandArg& a = c.args[i];
      EXPECT_FALSE(optional && !a.optional)
          << c.name << ": a required argument after an optional one";
      optional |= a.optional;
      if (a.type == ArgType::kRest) {
        EXPECT_EQ(i + 1, c.args.size()) << c.name << ": REST not last";
      }
      if (a.type == ArgType::kOnOff) {
        EXPECT_TRUE(c.checked) << c.name << ": toggle needs checked";
      }
    }
  }
  // Every action scripts, sessions and lessons used before the table still exists.
  for (const char* old : {"edit",    "reset",        "reset-seed", "reload",
                          "load",    "open",         "save",       "play",
                          "pause",   "step",         "screenshot", "action",
                          "undo",    "redo",         "revert",     "pin",
                          "unpin",   "unpin-all",    "restore",    "pin-row",
                          "seeds",   "cancel-seeds", "scrub",      "live",
                          "branch",  "save-session", "tab",        "switch-formation",
                          "wait",    "formation",    "slot",       "editor",
                          "click",   "overlay",      "legend",     "help",
                          "present", "ui-scale",     "angle-unit"})
    EXPECT_NE(FindCommand(old), nullptr) << old;
}

TEST(CommandTable, TheWindowPageTableIsTheGeneratedOne) {
  const std::string page = testing::ReadText(std::string(FORMSIM_SOURCE_DIR) + "/docs/window.md");
  const std::string begin = "<!-- commands:begin (formsim gui --list-commands --markdown) -->\n";
  const std::string end = "<!-- commands:end -->";
  const auto a = page.find(begin), b = page.find(end);
  ASSERT_NE(a, std::string::npos) << "docs/window.md has no generated command table";
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(page.substr(a + begin.size(), b - a - begin.size()), CommandTableMarkdown())
      << "regenerate it: formsim gui --list-commands --markdown";
}

TEST(CommandTable, HelpAndListsComeFromTheTable) {
  const std::string list = CommandListText(), usage = CommandUsageList();
  for (const Command& c : Commands()) {
    EXPECT_NE(list.find(c.name + " "), std::string::npos) << c.name;
    EXPECT_NE(usage.find(c.Usage()), std::string::npos) << c.name;
  }
  std::size_t keyed = 0;
  for (const Command& c : Commands()) keyed += !c.keys.empty();
  EXPECT_EQ(KeyHelpRows().size(), keyed);
  // --markdown alone would open a window: it is refused.
  const std::string dir = testing::TempDir("command_table_cli");
  EXPECT_NE(testing::RunShell(testing::Binary() + " gui --markdown", dir + "/log.txt"), 0);
  EXPECT_NE(testing::ReadText(dir + "/log.txt").find("requires --list-commands"),
            std::string::npos);
}

TEST(CommandTable, UnknownActionsNameTheClosest) {
  TableWindow w;
  const std::string why = w.ui().RunScriptAction("pinn 3");
  EXPECT_NE(why.find("unknown action 'pinn'"), std::string::npos) << why;
  EXPECT_NE(why.find("pin"), std::string::npos) << why;
  const std::string why2 = w.ui().RunScriptAction("sceenshot x.png");
  EXPECT_NE(why2.find("screenshot"), std::string::npos) << why2;
  const std::string huge(30000, 'x');
  EXPECT_LT(w.ui().RunScriptAction(huge).size(), 400u);
}

TEST(CommandTable, BadArgumentsAreRefusedNamingTheArgument) {
  TableWindow w;
  for (const Command& c : Commands()) {
    if (c.disabled && !c.disabled(w.ui()).empty()) continue;
    if (c.args.empty()) {
      const std::string why = w.ui().RunScriptAction(c.name + " surplus");
      EXPECT_NE(why.find("unexpected"), std::string::npos) << c.name << ": " << why;
      continue;
    }
    const CommandArg& a = c.args[0];
    if (a.type == ArgType::kWord || a.type == ArgType::kRest) continue;  // the handler decides
    const std::string why = w.ui().RunScriptAction(c.name + " @bad@");
    EXPECT_NE(why.find(c.name + ": " + a.name), std::string::npos) << c.name << ": " << why;
    if (!a.optional) {
      const std::string none = w.ui().RunScriptAction(c.name);
      EXPECT_NE(none.find(a.name), std::string::npos) << c.name << ": " << none;
    }
  }
  EXPECT_NE(w.ui().RunScriptAction("seeds 0").find("N expects a whole number in 1 ... 100000"),
            std::string::npos);
  EXPECT_NE(w.ui().RunScriptAction("ui-scale 1e308").find("SCALE"), std::string::npos);
}

TEST(CommandTable, EveryCommandRunsFromAScript) {
  const std::string dir = testing::TempDir("command_table_script");
  for (const Command& c : Commands()) {
    if (c.ends_program) continue;
    // Each command on a fresh window (a load or lesson changes the scenario); the formation
    // editor's structural changes on one without a switching: block.
    TableWindow w(c.name == "formation" || c.name == "shape" ? "formation_cascade7"
                                                             : "formation_switching");
    if (c.name.rfind("lesson-", 0) == 0) {
      // The lesson rows on a lesson at its prediction step, predicted (its action may run).
      ASSERT_EQ(w.ui().RunScriptAction("lesson lphi_time_constant"), "");
      ASSERT_EQ(w.ui().RunScriptAction("lesson-step 4"), "");
      ASSERT_EQ(w.ui().RunScriptAction("lesson-predict 1"), "");
    }
    ASSERT_EQ(w.ui().RunScriptAction("step"), "");  // a run to pin, scrub or branch from
    const std::string args = GoodArgs(c, w.ui(), dir);
    const std::string why = w.ui().RunScriptAction(c.name + (args.empty() ? "" : " " + args));
    // A few may be refused for the state they find (nothing to undo, no timeline); they must
    // say why, and the window goes on.
    if (!why.empty()) {
      EXPECT_TRUE(c.name == "undo" || c.name == "redo" || c.name == "cancel-seeds" ||
                  c.name == "branch" || c.name == "restore" || c.name == "pin-row" ||
                  c.name == "unpin" || c.name == "click" || c.name == "restore-session" ||
                  c.name == "discard-session" || c.name == "field-type" ||
                  c.name == "field-enter" || c.name == "field-escape")
          << c.name << " " << args << ": " << why;
    }
    for (int i = 0; i < 3; ++i) w.Frame();
  }
}

TEST(CommandTable, EveryCommandIsFoundByThePalette) {
  TableWindow w;
  for (const Command& c : Commands()) {
    if (c.script_only) continue;
    const auto entries = w.ui().PaletteEntries(c.name);
    bool found = false;
    for (const PaletteEntry& e : entries) found |= !e.tunable && e.name == c.name;
    EXPECT_TRUE(found) << c.name;
  }
  // A tunable by parts of its key, in any order.
  const auto entries = w.ui().PaletteEntries("k_l R2");
  ASSERT_FALSE(entries.empty());
  EXPECT_TRUE(entries.front().tunable);
  EXPECT_EQ(entries.front().name, "robots.R2.follow.k_l");
  // Enter in the palette puts the keyboard into that field.
  w.ui().CmdPalette("k_l R2");
  w.Frame();
  w.Frame();  // the field takes the keyboard
  w.Frame([](ImGuiIO& io) { io.KeysDown[ImGui::GetIO().KeyMap[ImGuiKey_Enter]] = true; });
  w.Frame();
  EXPECT_FALSE(w.ui().state().palette);
  EXPECT_EQ(w.ui().state().status, "tunable robots.R2.follow.k_l: type its value");
  for (int i = 0; i < 3; ++i) w.Frame();
  EXPECT_FALSE(w.ui().Find<ParametersPanel>()->FocusPending()) << "the field was not drawn";
  // The value entry (app/gui/value_entry.hpp) is open on it and has the keyboard.
  EXPECT_EQ(w.ui().Find<ParametersPanel>()->EntryKey(), "robots.R2.follow.k_l");
  EXPECT_TRUE(ImGui::GetIO().WantTextInput)
      << "the tunable's field did not take the keyboard (active " << ImGui::GetActiveID() << ")";
}

TEST(CommandTable, EveryMenuItemIsDrawnAndAClickRunsIt) {
  TableWindow w;
  std::set<std::string> tops;
  for (const Command& c : Commands())
    if (!c.script_only) tops.insert(TopOf(c.menu));
  for (const std::string& top : tops) {
    w.ui().RunScriptAction("menu " + top);
    w.Frame();
    w.Frame();
  }
  for (const Command& c : Commands()) {
    if (c.script_only) continue;
    EXPECT_EQ(w.ui().menu_items().count(c.name), 1u) << c.name << " has no menu item";
  }
  // Clicking items that need no argument runs them (and they become recent commands).
  for (const char* name : {"fit", "pin", "history", "legend"}) {
    const Command* c = FindCommand(name);
    ASSERT_NE(c, nullptr);
    w.ui().RunScriptAction("menu " + TopOf(c->menu));
    w.Frame();
    w.Frame();
    const auto rect = w.ui().menu_items().at(name);
    const ImVec2 mid(0.5f * (rect.first.x + rect.second.x), 0.5f * (rect.first.y + rect.second.y));
    w.Frame([&](ImGuiIO& io) { io.MousePos = mid; });
    w.Frame([&](ImGuiIO& io) {
      io.MousePos = mid;
      io.MouseDown[0] = true;
    });
    w.Frame([&](ImGuiIO& io) { io.MousePos = mid; });
    ASSERT_FALSE(w.ui().state().recent_commands.empty()) << name;
    EXPECT_EQ(w.ui().state().recent_commands.front(), name);
  }
}

TEST(CommandTable, KeysRunTheirRows) {
  TableWindow w;
  const long steps = w.ui().session().exp().steps();
  w.Frame([](ImGuiIO& io) { io.AddInputCharacter('.'); });
  EXPECT_EQ(w.ui().session().exp().steps(), steps + 1);
  w.Frame([](ImGuiIO& io) { io.AddInputCharacter('l'); });
  EXPECT_FALSE(w.ui().state().legend);
  w.Frame([](ImGuiIO& io) {
    io.KeyCtrl = true;
    io.KeysDown[int{'K'}] = true;  // GLFW's key code of a letter is its capital
  });
  EXPECT_TRUE(w.ui().state().palette);
  EXPECT_EQ(w.ui().PressKey("Esc"), "");
  EXPECT_FALSE(w.ui().state().palette);
  EXPECT_EQ(w.ui().PressKey("F1"), "");
  EXPECT_TRUE(w.ui().state().help);
}

TEST(CommandTable, FormationCommandsAreDisabledElsewhere) {
  TableWindow w("agv_fused");
  const std::string why = w.ui().RunScriptAction("editor add l_phi");
  EXPECT_NE(why.find("only for a formation scenario"), std::string::npos) << why;
  EXPECT_NE(w.ui().RunScriptAction("switch-formation").find("switching"), std::string::npos);
}

TEST(CommandTable, SwitchingScenariosKeepTheirStructure) {
  // A scenario with a switching: block names every follower's law and slot in its shapes: its
  // structure is greyed out with the reason (the editor's clicks are refused with it too), and
  // switching and slot drags stay.
  TableWindow sw("formation_switching");
  for (const char* change : {"formation remove R5", "shape wedge 0.6"})
    EXPECT_NE(sw.ui().RunScriptAction(change).find("its switching: block"), std::string::npos)
        << change;
  EXPECT_EQ(sw.ui().RunScriptAction("step"), "");
  EXPECT_EQ(sw.ui().RunScriptAction("switch-formation"), "");
}

}  // namespace
}  // namespace formsim::app
