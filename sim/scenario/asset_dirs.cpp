#include "sim/scenario/asset_dirs.hpp"

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#ifndef __EMSCRIPTEN__
#include <dlfcn.h>
#endif

namespace fs = std::filesystem;

namespace formsim::sim {

namespace {

bool HoldsScenarios(const fs::path& root) {
  std::error_code ec;
  return fs::is_directory(root / "scenarios", ec);
}

}  // namespace

std::vector<std::string> RunningCodeFiles() {
  std::vector<std::string> out;
#ifndef __EMSCRIPTEN__
  auto add = [&out](const fs::path& p) {
    std::error_code ec;
    const fs::path c = fs::canonical(p, ec);
    if (ec) return;
    for (const auto& o : out)
      if (o == c.string()) return;
    out.push_back(c.string());
  };
  // The object holding this code. A shared object (the Python module's _core.so) is named by
  // its path; the executable is named by argv[0] (program_invocation_name), which may be a bare
  // name found on PATH, so it is read from /proc/self/exe instead. Only this code's own file
  // counts: under Python, /proc/self/exe is the interpreter, whose share/ is not ours.
  Dl_info info{};
  const bool known = dladdr(reinterpret_cast<void*>(&RunningCodeFiles), &info) != 0 &&
                     info.dli_fname != nullptr && *info.dli_fname != 0;
  if (known && std::string(info.dli_fname) != program_invocation_name)
    add(info.dli_fname);
  else
    add("/proc/self/exe");
#endif
  return out;
}

std::string InstalledAssetsBeside(const std::string& file) {
  fs::path dir = fs::path(file).parent_path();
  // PREFIX/bin/formsim: one up; PREFIX/lib/python3/dist-packages/formsim/_core.so: four up.
  for (int up = 0; up < 4 && !dir.empty(); ++up) {
    dir = dir.parent_path();
    const fs::path share = dir / "share" / "formsim";
    if (HoldsScenarios(share)) return share.string();
    if (dir == dir.root_path()) break;
  }
  return "";
}

AssetRoot FindAssetRoot() {
  for (const std::string& file : RunningCodeFiles())
    if (std::string share = InstalledAssetsBeside(file); !share.empty())
      return {share, "installed beside " + file, true};
  if (const char* env = std::getenv("FORMSIM_ASSETS"); env != nullptr && *env != 0)
    return {env, "$FORMSIM_ASSETS", HoldsScenarios(env)};
  const std::string src = std::string(FORMSIM_SOURCE_DIR) + "/assets";
  return {src, "source tree", HoldsScenarios(src)};
}

std::string AssetDir(const std::string& sub) { return FindAssetRoot().path + "/" + sub; }

}  // namespace formsim::sim
