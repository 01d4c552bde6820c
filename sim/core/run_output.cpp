#include "sim/core/run_output.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace formsim::sim {

void PrepareOutputDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + dir + "': " + ec.message());
  const std::string probe = (fs::path(dir) / ".formsim_write_test").string();
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) throw std::runtime_error("output folder '" + dir + "' is not writable");
  std::fclose(f);
  fs::remove(probe, ec);
}

void WriteFileAtomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("error writing '" + path + "'");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot move '" + tmp + "' to '" + path + "': " + ec.message());
}

void WriteRunOutputs(const Experiment& exp, const std::string& dir) {
  PrepareOutputDir(dir);
  const std::string csv = (fs::path(dir) / "timeseries.csv").string();
  exp.recorder().WriteCsv(csv + ".tmp");
  std::error_code ec;
  fs::rename(csv + ".tmp", csv, ec);
  if (ec) throw std::runtime_error("cannot write '" + csv + "': " + ec.message());
  WriteFileAtomic((fs::path(dir) / "summary.json").string(), exp.Summary().Dump());
}

}  // namespace formsim::sim
