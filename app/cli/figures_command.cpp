#include "app/cli/figures_command.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/cli/cli_messages.hpp"
#include "app/cli/progress.hpp"
#include "app/export/export.hpp"
#include "app/export/figure_requests.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/thread_pool.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

// Rows kept in memory for the figures, as `formsim run` keeps them: the same figures.
constexpr std::size_t kHistoryRows = 20000;

struct Job {
  std::string file, name;
  pid_t pid = -1;
  int fd = -1;  ///< the worker's reports
  std::string buffer;
  double fraction = 0;
  bool done = false;
  long files = 0;
  int code = 0;
  std::string errors;
};

void WriteAll(int fd, const std::string& s) {
  std::size_t off = 0;
  while (off < s.size()) {
    const ssize_t n = write(fd, s.data() + off, s.size() - off);
    if (n <= 0) return;
    off += static_cast<std::size_t>(n);
  }
}

// Threads each running worker should use, one slot per job, shared with the workers (set by the
// parent, read by a worker between steps). Results do not depend on it.
class SharedThreads {
 public:
  explicit SharedThreads(std::size_t n) : n_(std::max<std::size_t>(n, 1)) {
    void* p = mmap(nullptr, n_ * sizeof(std::atomic<int>), PROT_READ | PROT_WRITE,
                   MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::runtime_error("figures: cannot map shared memory");
    slots_ = static_cast<std::atomic<int>*>(p);
    for (std::size_t i = 0; i < n_; ++i) new (&slots_[i]) std::atomic<int>(1);
  }
  ~SharedThreads() { munmap(slots_, n_ * sizeof(std::atomic<int>)); }
  SharedThreads(const SharedThreads&) = delete;
  SharedThreads& operator=(const SharedThreads&) = delete;
  std::atomic<int>& operator[](std::size_t i) { return slots_[i]; }

 private:
  std::size_t n_;
  std::atomic<int>* slots_ = nullptr;
};

// The worker: one scenario through the export path of `formsim run`, reporting on `fd` with
// lines "P <fraction>", "E <message>" and "F <files>", with the threads `threads` asks for (read
// again between steps: a worker left alone at the end takes the cores the others freed).
// Returns the exit code.
int Worker(const Job& job, ExportOptions opt, int fd, std::atomic<int>& threads) {
  try {
    int now = threads.load();
    sim::ThreadPool::SetDefaultThreads(now);
    sim::Session session(job.file, std::vector<sim::Override>{});
    session.exp().mutable_recorder().SetHistoryLimit(kHistoryRows);
    int last = -1;
    const ExportStats st = RunWithExport(session, opt, [&](const ExportProgress& p) {
      if (const int want = threads.load(std::memory_order_relaxed); want != now) {
        session.exp().SetThreads(want);  // between two steps
        now = want;
      }
      // Reports in steps of 1 %: the parent redraws its line at most 5 times a second.
      const int pct = static_cast<int>(p.fraction * 100);
      if (pct == last) return;
      last = pct;
      WriteAll(fd, "P " + std::to_string(p.fraction) + "\n");
    });
    int code = 0;
    if (!st.error.empty()) {
      WriteAll(fd, "E export failed: " + st.error + "\n");
      code = 4;
    }
    if (session.exp().status() == "numerical_fault") {
      WriteAll(fd, "E the run stopped at t = " + std::to_string(session.exp().time()) +
                       " s: " + session.exp().stop_reason() + " (figures show it up to there)\n");
      code = std::max(code, 3);
    }
    WriteAll(fd, "F " + std::to_string(st.figure_files + st.snapshots) + "\n");
    return code;
  } catch (const std::exception& e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    WriteAll(fd, "E " + msg + "\n");
    return 4;
  }
}

// Reads what a worker reported so far. At the end of its reports (the worker closed the pipe
// and is exiting) the pipe is closed here and no longer polled: a closed pipe polls ready at
// once, and polling it until the worker could be reaped spun the parent (24,618 wait4 calls
// for 16 scenarios, a fifth of the command's CPU).
void Drain(Job& job) {
  if (job.fd < 0) return;
  char buf[4096];
  for (;;) {
    const ssize_t n = read(job.fd, buf, sizeof(buf));
    if (n == 0) {
      close(job.fd);
      job.fd = -1;
      break;
    }
    if (n < 0) break;  // nothing more for now
    job.buffer.append(buf, static_cast<std::size_t>(n));
  }
  std::size_t nl;
  while ((nl = job.buffer.find('\n')) != std::string::npos) {
    const std::string line = job.buffer.substr(0, nl);
    job.buffer.erase(0, nl + 1);
    if (line.size() < 2) continue;
    const std::string rest = line.substr(2);
    if (line[0] == 'P') job.fraction = std::atof(rest.c_str());
    if (line[0] == 'F') job.files = std::atol(rest.c_str());
    if (line[0] == 'E') job.errors += (job.errors.empty() ? "" : "; ") + rest;
  }
}

// Every option, checked before anything runs: the export options every scenario shares.
ExportOptions FiguresExportOptions(const FiguresOptions& o) {
  if (o.out_dir.empty()) throw std::runtime_error("figures: --out DIR is required");
  CheckFolderName(o.out_dir, "--out", "figures go into DIR/<scenario>/");
  ExportOptions opt;
  opt.plot_formats = ParseFigureFormats(o.formats, "--plot-format");
  opt.plot_size = ParseFigureSize(o.plot_size, "--plot-size");
  ParseSize(o.size, &opt.width, &opt.height, "--size");
  opt.dpi = ParseDpi(o.dpi);
  opt.theme = ParseTheme(o.theme, "--theme");
  opt.titles = ParseTitleMode(o.titles, "--titles");
  if (!o.log_y.empty()) opt.log_y = ParseFigureNames(o.log_y, "--log-y");
  opt.whole_run = true;  // the world view shows the whole run
  if (o.jobs < 0) throw std::runtime_error("--jobs must be 0 (one per core) or more");
  return opt;
}

// One job per scenario. Each is loaded (and stepped once) here, so a bad scenario or bad figure
// markup fails before anything is drawn; each --log-y name must be a figure of some scenario.
std::vector<Job> FiguresJobs(const FiguresOptions& o, const ExportOptions& opt) {
  std::vector<Job> jobs;
  std::vector<sim::FigureSpec> all_figures;
  const std::vector<std::string> names =
      o.scenarios.empty() ? sim::ShippedScenarios() : o.scenarios;
  for (const std::string& name : names) {
    Job job;
    job.file = sim::ResolveScenario(name);
    job.name = fs::path(job.file).stem().string();
    for (const Job& other : jobs)
      if (other.name == job.name)
        throw std::runtime_error("figures: two scenarios are called '" + job.name +
                                 "' (their figures would overwrite each other)");
    const std::vector<sim::FigureSpec> figs = ProbeFigures(job.file, {});
    CheckFigureRequests(figs, {});
    all_figures.insert(all_figures.end(), figs.begin(), figs.end());
    jobs.push_back(std::move(job));
  }
  CheckFigureRequests(all_figures, opt.log_y);
  if (jobs.empty()) throw std::runtime_error("figures: no scenario to draw");
  return jobs;
}

// Each scenario's export options: its figures and world views in DIR/<scenario>/, its outputs
// checked (folders, fonts, ffmpeg...) before the first worker starts.
std::vector<ExportOptions> FiguresJobOptions(const std::vector<Job>& jobs, const ExportOptions& opt,
                                             const std::string& out_dir) {
  std::vector<ExportOptions> job_opts;
  for (const Job& job : jobs) {
    ExportOptions j = opt;
    j.plots_dir = (fs::path(out_dir) / job.name).string();
    for (FigureFormat f : opt.plot_formats)
      j.snapshots.push_back(j.plots_dir + "/world." + FormatExtension(f));
    PrepareExport(j);
    job_opts.push_back(std::move(j));
  }
  return job_opts;
}

// Starts `job`'s worker in a child process that reports on a pipe (read without blocking).
void StartFiguresWorker(Job& job, const ExportOptions& opt, std::atomic<int>& threads) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("figures: cannot create a pipe");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("figures: cannot start a worker process");
  if (pid == 0) {
    close(fds[0]);
    const int code = Worker(job, opt, fds[1], threads);
    close(fds[1]);
    std::fflush(stdout);
    std::fflush(stderr);
    _exit(code);
  }
  close(fds[1]);
  fcntl(fds[0], F_SETFL, fcntl(fds[0], F_GETFL) | O_NONBLOCK);
  job.pid = pid;
  job.fd = fds[0];
}

// Waits for reports (or a worker's end) for up to 0.2 s and reads them. A worker whose reports
// ended is only waited for: every 2 ms until it has exited.
void PollFiguresWorkers(std::vector<Job>& jobs, const std::vector<std::size_t>& running) {
  std::vector<pollfd> pfds;
  bool exiting = false;
  for (std::size_t i : running) {
    if (jobs[i].fd >= 0) pfds.push_back({jobs[i].fd, POLLIN, 0});
    exiting = exiting || jobs[i].fd < 0;
  }
  poll(pfds.data(), pfds.size(), exiting ? 2 : 200);
  for (const pollfd& p : pfds)
    if (p.revents & (POLLIN | POLLHUP | POLLERR))
      for (std::size_t i : running)
        if (jobs[i].fd == p.fd) Drain(jobs[i]);
}

// True when `job`'s worker, its reports ended, has exited: its exit code and, when it died of a
// signal, the signal are taken into the job.
bool ReapFiguresWorker(Job& job) {
  int status = 0;
  if (job.fd >= 0 || waitpid(job.pid, &status, WNOHANG) != job.pid) return false;
  job.done = true;
  job.fraction = 1;
  job.code = WIFEXITED(status) ? WEXITSTATUS(status) : 4;
  if (!WIFEXITED(status))
    job.errors += (job.errors.empty() ? "" : "; ") + std::string("the worker died (signal ") +
                  std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0) + ")";
  return true;
}

// The progress line: every scenario counts the same (their costs are not known before they run).
void ShowFiguresProgress(ProgressLine& bar, const std::vector<Job>& jobs,
                         const std::vector<std::size_t>& running, std::size_t finished) {
  double done = 0;
  long files = 0;
  for (const Job& j : jobs) done += j.fraction, files += j.files;
  std::string now;
  for (std::size_t i : running) now += (now.empty() ? "" : ", ") + jobs[i].name;
  bar.Update(done / static_cast<double>(jobs.size()),
             std::to_string(finished) + "/" + std::to_string(jobs.size()) + " scenarios, " +
                 std::to_string(files) + " files" + (now.empty() ? "" : "  (" + now + ")"));
}

// Runs every job's worker, at most `max_jobs` at once, until all have exited. The cores are
// shared out among the running workers: one thread each while there are more scenarios than
// cores; the last ones get the cores the finished ones free.
void RunFiguresWorkers(std::vector<Job>& jobs, const std::vector<ExportOptions>& job_opts,
                       int cores, int max_jobs, ProgressLine& bar) {
  SharedThreads threads(jobs.size());
  auto share_cores = [&](const std::vector<std::size_t>& running, bool queue_empty) {
    const int busy = queue_empty ? static_cast<int>(running.size()) : max_jobs;
    for (std::size_t i : running)
      threads[i].store(std::max(1, cores / std::max(1, busy)), std::memory_order_relaxed);
  };
  std::size_t next = 0, finished = 0;
  std::vector<std::size_t> running;
  while (finished < jobs.size()) {
    // Start workers while there are free cores.
    while (next < jobs.size() && static_cast<int>(running.size()) < max_jobs) {
      std::vector<std::size_t> will_run = running;
      will_run.push_back(next);
      share_cores(will_run, next + 1 == jobs.size());
      StartFiguresWorker(jobs[next], job_opts[next], threads[next]);
      running.push_back(next++);
    }
    PollFiguresWorkers(jobs, running);
    for (std::size_t k = 0; k < running.size();) {
      if (ReapFiguresWorker(jobs[running[k]])) {
        ++finished;
        running.erase(running.begin() + static_cast<long>(k));
        if (next == jobs.size()) share_cores(running, true);
        continue;
      }
      ++k;
    }
    ShowFiguresProgress(bar, jobs, running, finished);
  }
}

}  // namespace

int FiguresCommand(const FiguresOptions& o) {
  // Every option and scenario is checked before anything runs.
  const ExportOptions opt = FiguresExportOptions(o);
  std::vector<Job> jobs = FiguresJobs(o, opt);
  sim::PrepareOutputDir(o.out_dir);
  const std::vector<ExportOptions> job_opts = FiguresJobOptions(jobs, opt, o.out_dir);

  const int cores = sim::ThreadPool::HardwareThreads();
  const int max_jobs = o.jobs > 0 ? o.jobs : cores;
  ProgressLine bar(!o.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  RunFiguresWorkers(jobs, job_opts, cores, max_jobs, bar);
  bar.Done();

  int rc = 0;
  long files = 0;
  for (const Job& j : jobs) {
    files += j.files;
    if (!j.errors.empty()) PrintCliError(j.name + ": " + j.errors);
    rc = std::max(rc, j.code);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!o.quiet)
    sim::Print(stdout, "wrote %ld files for %zu scenarios into %s in %.1f s (%d workers)\n", files,
               jobs.size(), o.out_dir.c_str(), wall, max_jobs);
  return rc;
}

}  // namespace formsim::app
