#include "sim/core/run_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace formsim::sim {

void PrepareOutputDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + dir + "': " + ec.message());
  if (!fs::is_directory(dir, ec)) throw std::runtime_error("output folder '" + dir + "' is not a folder");
  const std::string probe = (fs::path(dir) / ".formsim_write_test").string();
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) throw std::runtime_error("output folder '" + dir + "' is not writable");
  std::fclose(f);
  fs::remove(probe, ec);
}

void WriteFileAtomic(const std::string& path, const std::string& text, bool sync) {
  // A device or pipe (/dev/stdout, a link to /dev/full) is written as it is, never renamed over.
  struct stat st {};
  const bool special = ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
  const std::string tmp = special ? path : path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  // Every write checked, then flushed to the disk before the rename makes the file visible:
  // a full disk leaves the previous file (or none), never a truncated one.
  std::size_t done = 0;
  std::string error;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = std::strerror(errno);
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (sync && !special && error.empty() && ::fsync(fd) != 0) error = std::strerror(errno);
  if (::close(fd) != 0 && error.empty()) error = std::strerror(errno);
  if (!error.empty()) {
    if (!special) std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + error);
  }
  if (special) return;
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = std::strerror(errno);
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot move '" + tmp + "' to '" + path + "': " + error);
  }
}

void SyncFileSystem(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot open '" + dir + "': " + std::strerror(errno));
  const int rc = ::syncfs(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw std::runtime_error("cannot sync '" + dir + "' to disk: " + std::strerror(err));
}

std::string CsvPath(const std::string& dir) { return (fs::path(dir) / "timeseries.csv").string(); }

void WriteRunOutputs(Experiment& exp, const std::string& dir) {
  PrepareOutputDir(dir);
  // The summary first (small), then the rows: whatever fails, the other is still written.
  std::string error;
  try {
    WriteFileAtomic((fs::path(dir) / "summary.json").string(), exp.Summary().Dump());
  } catch (const std::exception& e) {
    error = e.what();
  }
  try {
    Recorder& rec = exp.mutable_recorder();
    if (rec.streaming())
      rec.FinishStream();
    else
      rec.WriteCsv(CsvPath(dir));
  } catch (const std::exception& e) {
    error += (error.empty() ? "" : "; ") + std::string(e.what());
  }
  if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace formsim::sim
