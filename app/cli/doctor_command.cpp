#include "app/cli/doctor_command.hpp"

#include <cairo.h>
#include <nlopt.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/export/video_writer.hpp"
#include "app/render/fonts.hpp"
#include "app/render/gl_api.hpp"
#include "app/render/offscreen_context.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/provenance.hpp"
#include "sim/scenario/asset_dirs.hpp"
#include "sim/study/tune_plan.hpp"

#ifndef FORMSIM_BUILD_TYPE
#define FORMSIM_BUILD_TYPE "unknown"
#endif

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

// One line of the report: "  ok       name          detail".
void Row(bool ok, const std::string& name, const std::string& detail) {
  sim::Print(stdout, "  %-8s %-15s %s\n", ok ? "ok" : "missing", name.c_str(), detail.c_str());
}

int CountFiles(const fs::path& dir, const std::string& ext) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ext) ++n;
  return n;
}

// The shell's single-quoted form of `s`.
std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs `command` and returns its first line of output ("" when it failed).
std::string FirstLine(const std::string& command, int* status) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) {
    *status = -1;
    return out;
  }
  std::array<char, 512> buf{};
  if (std::fgets(buf.data(), buf.size(), p) != nullptr) out = buf.data();
  while (std::fgets(buf.data(), buf.size(), p) != nullptr) {
  }
  *status = pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

// The folders a Python module built or installed with this program would be in: the build
// tree's python/, an install prefix's lib/python3/dist-packages and lib/python3.X/dist-packages.
std::vector<fs::path> PythonModuleDirs(const fs::path& program) {
  std::vector<fs::path> dirs;
  const fs::path bin = program.parent_path();
  std::error_code ec;
  auto consider = [&](const fs::path& d) {
    if (fs::is_directory(d / "formsim", ec)) dirs.push_back(d);
  };
  consider(bin / "python");
  consider(bin.parent_path() / "lib" / "python3" / "dist-packages");
  for (const auto& e : fs::directory_iterator(bin.parent_path() / "lib", ec))
    if (e.path().filename().string().rfind("python3.", 0) == 0) consider(e.path() / "dist-packages");
  return dirs;
}

void PythonRow(const fs::path& program) {
  const std::string python = "/usr/bin/python3";
  if (!fs::exists(python)) {
    Row(false, "Python module", "no /usr/bin/python3 (Debian: python3 python3-numpy)");
    return;
  }
  const std::string probe =
      " -c 'import formsim, os; print(os.path.dirname(formsim.__file__))' 2>&1";
  int status = 0;
  // A module installed or built beside this program is the one to report; else any on the path.
  if (const std::vector<fs::path> dirs = PythonModuleDirs(program); !dirs.empty()) {
    const fs::path& d = dirs.front();
    const std::string line =
        FirstLine("PYTHONPATH=" + Quote(d.string()) + " " + python + probe, &status);
    if (status == 0)
      Row(true, "Python module", line + " (python3 with PYTHONPATH=" + d.string() + ")");
    else
      Row(false, "Python module",
          d.string() + "/formsim does not import: " + line + " (Debian: python3-numpy)");
    return;
  }
  const std::string line = FirstLine(python + probe, &status);
  if (status == 0)
    Row(true, "Python module", line + " (import formsim)");
  else
    Row(false, "Python module",
        "`import formsim` fails and none was installed beside this program (build with "
        "pybind11-dev python3-dev python3-numpy, or install the .deb)");
}

}  // namespace

std::string VersionLine() {
  std::string v = sim::FormsimVersion();  // "0.1.0 (git 1a2b3c4)"
  const std::string type = FORMSIM_BUILD_TYPE;
  if (!v.empty() && v.back() == ')')
    v.insert(v.size() - 1, ", " + type);
  else
    v += " (" + type + ")";
  return "formsim " + v;
}

int DoctorCommand() {
  int rc = 0;
  std::fputs((VersionLine() + "\n").c_str(), stdout);
  const std::vector<std::string> code = sim::RunningCodeFiles();
  const fs::path program = code.empty() ? fs::path() : fs::path(code.front());
  std::fputs(("program          " + (program.empty() ? "?" : program.string()) + "\n").c_str(),
             stdout);

  const sim::AssetRoot root = sim::FindAssetRoot();
  std::fputs(("assets           " + root.path + " (" + root.how + ")\n").c_str(), stdout);
  if (!root.found) {
    std::fputs(
        "  error: no scenarios/ there; install formsim (share/formsim), or set "
        "FORMSIM_ASSETS to a folder holding scenarios/, lessons/, fuzzy/ and fonts/\n",
        stdout);
    rc = 1;
  }
  struct Folder {
    const char* name;
    const char* ext;
    const char* what;
  };
  for (const Folder& f : {Folder{"scenarios", ".yaml", "scenarios"},
                          Folder{"lessons", ".yaml", "lessons"},
                          Folder{"fuzzy", ".fll", "rule file(s)"}}) {
    const fs::path dir = sim::AssetDir(f.name);
    const int n = CountFiles(dir, f.ext);
    sim::Print(stdout, "  %-14s %s (%d %s)\n", f.name, dir.c_str(), n, f.what);
    if (n == 0) rc = 1;
  }
  for (FontRole role : {FontRole::kUi, FontRole::kTitle, FontRole::kMono}) {
    const std::string file = FontSpecOf(role).file;
    const std::string path = FindFont(file);
    if (path.empty()) {
      sim::Print(stdout,
                 "  %-14s %s: not found in %s or /usr/share/fonts/truetype/dejavu (Debian: "
                 "fonts-dejavu-core)\n",
                 "fonts", file.c_str(), sim::AssetDir("fonts").c_str());
      rc = 1;
    } else {
      sim::Print(stdout, "  %-14s %s\n", "fonts", path.c_str());
    }
  }

  std::fputs("optional parts\n", stdout);
  try {
    OffscreenContext ctx(16, 16);
    Row(true, "GL renderer", GlRendererText() + " (OSMesa: frames, snapshots, PNG figures)");
  } catch (const std::exception& e) {
    Row(false, "GL renderer", std::string(e.what()) + " (Debian: libosmesa6)");
    rc = 1;
  }
  Row(true, "Cairo", std::string(cairo_version_string()) + " (PDF figures)");
  int major = 0, minor = 0, bugfix = 0;
  nlopt_version(&major, &minor, &bugfix);
  std::string methods;
  for (const std::string& m : sim::TuneAlgorithms()) methods += (methods.empty() ? "" : ", ") + m;
  Row(true, "NLopt",
      std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(bugfix) +
          ": " + methods + " (formsim tune)");
  const std::string ffmpeg = FindOnPath("ffmpeg");
  Row(!ffmpeg.empty(), "ffmpeg",
      ffmpeg.empty() ? "not on PATH: --video and --gif need it (Debian: ffmpeg)"
                     : ffmpeg + " (--video, --gif)");
  PythonRow(program);
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display != nullptr && *display != 0) || (wayland != nullptr && *wayland != 0))
    Row(true, "display",
        std::string(display != nullptr && *display != 0 ? "DISPLAY=" + std::string(display)
                                                        : "WAYLAND_DISPLAY=" + std::string(wayland)) +
            " (formsim gui)");
  else
    Row(false, "display",
        "none: `formsim gui` needs one (or xvfb-run from Debian's xvfb); every other command "
        "works without");
  return rc;
}

}  // namespace formsim::app
