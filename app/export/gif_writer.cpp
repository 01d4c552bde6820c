#include "app/export/gif_writer.hpp"

#include <sys/wait.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "app/export/video_writer.hpp"
#include "sim/core/number_format.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

bool ExitedOk(int status) {
  return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

void GifWriter::CheckAvailable(const std::string& path, double fps, int out_width) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".gif")
    throw std::runtime_error("--gif '" + path + "': the file name must end in .gif");
  if (!(fps > 0 && fps <= 50))
    throw std::runtime_error(
        "--gif-fps must be in (0, 50] (GIF frame delays are in 1/100 s), "
        "got " +
        sim::FormatSignificant(fps));
  if (out_width < 64 || out_width > 4096)
    throw std::runtime_error("--gif-width must be 64 ... 4096 pixels, got " +
                             std::to_string(out_width));
  if (FindOnPath("ffmpeg").empty())
    throw std::runtime_error(
        "--gif needs the program 'ffmpeg', which is not on PATH (Debian: apt-get install ffmpeg)");
}

GifWriter::GifWriter(const std::string& path, int width, int height, double fps, int out_width)
    : path_(path), frame_bytes_(static_cast<std::size_t>(width) * height * 4), fps_(fps) {
  CheckAvailable(path, fps, out_width);
  std::error_code ec;
  std::string tmpl = (fs::temp_directory_path(ec) / "formsim_gif_XXXXXX").string();
  const char* dir = mkdtemp(tmpl.data());
  if (dir == nullptr)
    throw std::runtime_error("--gif: cannot create a temporary folder (" + tmpl + ")");
  tmp_dir_ = dir;
  std::signal(SIGPIPE, SIG_IGN);  // a dying ffmpeg becomes a write error, not a crash
  // One pass over the stream: the palette of every frame (stats_mode=full: the picture as a
  // whole, not only what changes) and a lossless copy of the frames for the second pass.
  std::ostringstream scale;
  if (out_width != width) scale << "scale=" << out_width << ":-2:flags=lanczos,";
  std::ostringstream cmd;
  cmd << "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgba -s " << width << "x" << height
      << " -r " << fps << " -i - -filter_complex \"[0:v]" << scale.str()
      << "format=rgb24,split[a][b];[a]palettegen=max_colors=256:stats_mode=full[p]\""
      << " -map \"[p]\" -update 1 " << ShellQuote(tmp_dir_ + "/palette.png")
      << " -map \"[b]\" -c:v ffv1 " << ShellQuote(tmp_dir_ + "/frames.mkv");
  pipe_ = popen(cmd.str().c_str(), "w");
  if (pipe_ == nullptr) {
    Cleanup();
    throw std::runtime_error("cannot start ffmpeg for " + path);
  }
}

GifWriter::~GifWriter() {
  if (pipe_ != nullptr) pclose(pipe_);
  Cleanup();
}

void GifWriter::Cleanup() {
  if (tmp_dir_.empty()) return;
  std::error_code ec;
  fs::remove_all(tmp_dir_, ec);
  tmp_dir_.clear();
}

void GifWriter::Write(const std::vector<std::uint8_t>& rgba) {
  if (rgba.size() != frame_bytes_) throw std::runtime_error("GIF frame has the wrong size");
  if (std::fwrite(rgba.data(), 1, rgba.size(), pipe_) != rgba.size())
    throw std::runtime_error("ffmpeg stopped accepting frames for " + path_ +
                             " (see its message above)");
  ++frames_;
}

void GifWriter::Close() {
  if (pipe_ == nullptr) return;
  const int first = pclose(pipe_);
  pipe_ = nullptr;
  if (!ExitedOk(first)) {
    Cleanup();
    throw std::runtime_error("ffmpeg failed collecting the GIF frames for " + path_);
  }
  // Second pass: every frame onto the palette, only the changed rectangle stored per frame,
  // looping for ever. No dithering: our pictures are flat colours and thin lines, where
  // dithering adds noise and size.
  const std::string partial = PartialPath(path_);
  std::ostringstream cmd;
  cmd << "ffmpeg -y -loglevel error -i " << ShellQuote(tmp_dir_ + "/frames.mkv") << " -i "
      << ShellQuote(tmp_dir_ + "/palette.png")
      << " -lavfi \"paletteuse=dither=none:diff_mode=rectangle\" -r " << fps_ << " -loop 0 -f gif "
      << ShellQuote(partial);
  const int second = std::system(cmd.str().c_str());
  Cleanup();
  FinishPartial(second, partial, path_);
}

}  // namespace formsim::app
