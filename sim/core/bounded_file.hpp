#pragma once
/// \file The one way formsim reads a file a user hands it (scenarios, lessons, session and
/// history records, sweep manifests and run files, fuzzy rule bases, `--script` files, the
/// window's settings): only regular files, and never more than a stated number of bytes, so
/// that `/dev/zero`, a FIFO, a folder or a runaway file is refused with a message naming it
/// instead of filling the memory or blocking.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace formsim::sim {

/// The largest text file formsim reads: 4 MiB (the largest shipped scenario, 1000 robots, is
/// about 200 kB; a session record holds a few scenario texts and its edits).
constexpr std::size_t kMaxTextFileBytes = std::size_t{4} << 20;

/// A file that was refused or could not be read. what() is "FILE: reason".
class FileReadError : public std::runtime_error {
 public:
  FileReadError(const std::string& file, const std::string& reason)
      : std::runtime_error(file + ": " + reason), file_(file), reason_(reason) {}
  const std::string& file() const { return file_; }
  /// The message without the file name, e.g. "is not a regular file (a device)".
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, reason_;
};

/// Reads `file` whole when it is a regular file of at most `limit` bytes. Opens it without
/// blocking (a FIFO never waits for a writer), checks the opened descriptor with fstat and
/// then reads at most limit + 1 bytes, so a file that grows while it is read is refused too.
/// Throws FileReadError naming the file: missing or unreadable, not a regular file (a folder,
/// a device such as /dev/zero, a FIFO, a socket), or larger than `limit` (the limit in the
/// message).
std::string ReadBoundedFile(const std::string& file, std::size_t limit = kMaxTextFileBytes);

/// `bytes` as text for messages: "4 MiB", "512 kB", "100 bytes".
std::string ByteSizeText(std::size_t bytes);

}  // namespace formsim::sim
