#include "sim/core/bounded_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace formsim::sim {
namespace {

// Closes the descriptor on every path out.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

}  // namespace

std::string ByteSizeText(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0)
    return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= 1000 && bytes % 1000 == 0) return std::to_string(bytes / 1000) + " kB";
  return std::to_string(bytes) + " bytes";
}

std::string ReadBoundedFile(const std::string& file, std::size_t limit) {
  Fd f;
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  do {
    f.fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  } while (f.fd < 0 && errno == EINTR);
  if (f.fd < 0)
    throw FileReadError(file, std::string("cannot open the file: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0)
    throw FileReadError(file, std::string("cannot read the file: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw FileReadError(file, std::string("is not a regular file (") + KindOf(st.st_mode) + ")");
  const auto too_large = [&](const std::string& size) {
    return FileReadError(file, "is larger than " + ByteSizeText(limit) + " (" + size +
                                   "), the most formsim reads from one file");
  };
  if (st.st_size < 0 || static_cast<unsigned long long>(st.st_size) > limit)
    throw too_large(std::to_string(static_cast<long long>(st.st_size)) + " bytes");
  // Back to blocking reads (a regular file never blocks, but some file systems honour the flag).
  const int flags = ::fcntl(f.fd, F_GETFL);
  if (flags >= 0) ::fcntl(f.fd, F_SETFL, flags & ~O_NONBLOCK);
  std::string out;
  out.resize(static_cast<std::size_t>(st.st_size) + 1);
  std::size_t have = 0;
  // At most limit + 1 bytes: a file that grew since fstat is refused, never read on.
  const std::size_t most = limit + 1;
  for (;;) {
    if (have == out.size()) {
      if (out.size() >= most) break;
      out.resize(std::min(most, out.size() * 2 + 4096));
    }
    const ssize_t n = ::read(f.fd, out.data() + have, out.size() - have);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileReadError(file, std::string("cannot read the file: ") + std::strerror(errno));
    }
    if (n == 0) break;
    have += static_cast<std::size_t>(n);
  }
  if (have > limit) throw too_large("it grew while it was read");
  out.resize(have);
  return out;
}

}  // namespace formsim::sim
