#pragma once
/// \file Where the shipped assets (scenarios, lessons, fuzzy rule files, fonts) are found, so that
/// an installed formsim, a moved install prefix and a developer's build tree all find them.
///
/// Order (the first that holds a `scenarios` folder wins):
///  1. installed: `share/formsim` beside the program, found from the file of the running code
///     (the formsim executable, `PREFIX/bin`, or the Python module, `PREFIX/lib/python3/
///     dist-packages/formsim`) by walking up at most four folders; nothing is compiled in, so a
///     moved prefix still works;
///  2. `$FORMSIM_ASSETS`;
///  3. the source tree's `assets/` (developers' builds).

#include <string>
#include <vector>

namespace formsim::sim {

/// The folder the assets were found in and how.
struct AssetRoot {
  std::string path;  ///< e.g. "/usr/share/formsim" or "/home/u/formsim/assets"
  std::string how;   ///< "installed beside /usr/bin/formsim", "$FORMSIM_ASSETS", "source tree"
  bool found = false;  ///< false: none of the three holds scenarios (path is the source tree's)
};

/// Looks the asset root up (not cached: $FORMSIM_ASSETS may be set after start, as the page does).
AssetRoot FindAssetRoot();
/// `FindAssetRoot().path + "/" + sub` ("scenarios", "lessons", "fuzzy", "fonts").
std::string AssetDir(const std::string& sub);
/// The file of the running code: the shared object holding this function (the Python module),
/// else the executable (/proc/self/exe). A canonical path; empty where the platform has none.
std::vector<std::string> RunningCodeFiles();
/// The `share/formsim` folder an installed copy of the code in `file` would use, or "" when no
/// ancestor (up to four folders above) holds `share/formsim/scenarios`.
std::string InstalledAssetsBeside(const std::string& file);

}  // namespace formsim::sim
