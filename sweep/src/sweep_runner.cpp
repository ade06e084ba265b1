#include "talus/sweep/sweep_runner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <thread>
#include <tuple>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/progress_line.hpp"

namespace talus {
namespace {

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

constexpr int kInputErrorExit = 1;  ///< `talus` exit code for bad input: not retried
constexpr int kNoResultExit = 2;    ///< plan/profile/baseline: a result saying "no path"

std::string results_file_name(int rank) {
  return rank == 0 ? "results.jsonl" : "results.rank-" + std::to_string(rank) + ".jsonl";
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

/// A results file's size limit [bytes]: a million records of a kilobyte.
constexpr std::size_t kMaxResultsFileBytes = std::size_t{1} << 30;
/// A record's deepest nesting of arrays and objects: the sweep writes depth 3 (a record,
/// its parameters or figures, a vector among them); JSON nested deeper is not a record, and
/// nesting by the hundred thousand would exhaust the stack of a recursive destructor.
constexpr int kMaxRecordDepth = 64;

/// Nesting depth of the JSON text `line` (brackets outside strings), stopping past `limit`.
int json_depth(std::string_view line, int limit) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : line) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit) return deepest;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

/// The lines of a results file; a last line without its newline is torn
/// (the writer died in the middle of it) and left out, as is a line that is not
/// a record (not JSON, no case_id, nested beyond kMaxRecordDepth): its case runs
/// again. With `repair` the file is cut back to its last complete line, so
/// appends start cleanly. A missing file has no records; anything but a regular
/// file (a FIFO, a link to a device) or a file beyond kMaxResultsFileBytes is an
/// InputError (read_input_file), before it is opened.
std::vector<Json> read_records_file(const fs::path& path, bool repair) {
  std::vector<Json> records;
  std::error_code missing;
  if (!fs::exists(fs::symlink_status(path, missing))) return records;
  const std::string text = read_input_file(path.string(), kMaxResultsFileBytes);
  const std::size_t complete = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  std::size_t begin = 0;
  while (begin < complete) {
    const std::size_t end = text.find('\n', begin);
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (line.empty() || json_depth(line, kMaxRecordDepth) > kMaxRecordDepth) continue;
    Json record = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (record.is_object() && record.contains("case_id")) records.push_back(std::move(record));
  }
  if (repair && complete < text.size()) {
    std::error_code ignored;
    fs::resize_file(path, complete, ignored);
    if (ignored) throw Error("cannot repair the torn last line of " + path.string());
  }
  return records;
}

/// Holds DIR's lock for the sweep's lifetime.
class SweepLock {
 public:
  SweepLock(const fs::path& dir, int rank) {
    const fs::path path = dir / (rank == 0 ? std::string(".talus-sweep.lock")
                                           : ".talus-sweep.rank-" + std::to_string(rank) + ".lock");
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError("--out: cannot create the lock " + path.string());
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw InputError("--out: " + dir.string() + " is in use by another sweep");
    }
  }
  ~SweepLock() { ::close(fd_); }
  SweepLock(const SweepLock&) = delete;
  SweepLock& operator=(const SweepLock&) = delete;

 private:
  int fd_ = -1;
};

/// Appends whole lines to a results file, each with one write().
class RecordWriter {
 public:
  explicit RecordWriter(const fs::path& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError("--out: cannot write " + path.string());
  }
  ~RecordWriter() { ::close(fd_); }
  RecordWriter(const RecordWriter&) = delete;
  RecordWriter& operator=(const RecordWriter&) = delete;
  void append(const Json& record) {
    const std::string line = record.dump() + "\n";
    std::size_t written = 0;
    while (written < line.size()) {
      const ssize_t n = ::write(fd_, line.data() + written, line.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw Error("cannot append to " + path_.string() + ": " + std::strerror(errno));
      written += static_cast<std::size_t>(n);
    }
    // No fdatasync: one write() puts the whole line in the kernel, so a
    // killed sweep loses nothing; only a machine crash can lose the last
    // lines, whose cases are then simply redone (fdatasync cost 5 ms a case here).
  }

 private:
  fs::path path_;
  int fd_ = -1;
};

/// The first JSON object a job printed (the CLI's commands print one).
Json job_output(const fs::path& stdout_file) {
  std::ifstream in(stdout_file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::size_t brace = text.find('{');
  if (brace == std::string::npos) return Json::object();
  Json parsed = Json::parse(text.substr(brace), nullptr, false);
  return parsed.is_object() ? parsed : Json::object();
}

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  const std::string prefix = "talus: error: ";
  if (line.rfind(prefix, 0) == 0) line = line.substr(prefix.size());
  return line;
}

/// The job's key figures: its scalar output fields, timings left out (they
/// are the only ones that change from run to run).
Json key_figures(const Json& output) {
  Json figures = Json::object();
  for (const auto& [key, value] : output.items()) {
    if (key == "status" || key.find("seconds") != std::string::npos) continue;
    if (value.is_primitive()) figures[key] = value;
  }
  return figures;
}

/// The noop job: a worker that sleeps, crashes or prints a value, for
/// testing the sweep machinery and measuring its overhead per case.
int run_noop(const SweepCase& c) {
  const Json& p = c.parameters;
  if (p.contains("sleep") && p.at("sleep").is_number()) {
    std::this_thread::sleep_for(std::chrono::duration<double>(p.at("sleep").get<double>()));
  }
  if (p.contains("crash") && p.at("crash") == true) std::abort();
  Json out = {{"status", "ok"}};
  if (p.contains("value")) out["value"] = p.at("value");
  std::cout << out.dump() << "\n";
  return 0;
}

/// In the worker process: run the case's commands, stop at the first that fails.
int run_case(const SweepConfig& config, const SweepCase& c, const PreparedCase& prepared,
             const SweepOptions& options) {
  try {
    if (config.job == "noop") return run_noop(c);
    int code = 0;
    for (const std::vector<std::string>& command : prepared.commands) {
      code = options.run_command(command);
      if (code != 0) break;
    }
    return code;
  } catch (const std::exception& e) {
    std::cerr << "talus: error: " << e.what() << "\n";
    return kInputErrorExit;
  }
}

struct Worker {
  pid_t pid = -1;
  int done_fd = -1;  ///< read end of a pipe the worker holds open until it exits
  std::size_t case_index = 0;
  int attempt = 1;
  Clock::time_point start, deadline;
};

/// How a worker ended.
struct Ending {
  bool retry = false;  ///< crashed or hung
  int exit_code = -1;
  std::string reason;
};

Ending ending_of(int wait_status, bool timed_out, double limit) {
  Ending e;
  if (timed_out) {
    e.retry = true;
    std::ostringstream text;
    text << "ran longer than the case time limit of " << limit << " s and was killed";
    e.reason = text.str();
  } else if (WIFSIGNALED(wait_status)) {
    e.retry = true;
    const int sig = WTERMSIG(wait_status);
    e.reason = "worker killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  } else if (WIFEXITED(wait_status)) {
    e.exit_code = WEXITSTATUS(wait_status);
    if (e.exit_code != 0 && e.exit_code != kInputErrorExit && e.exit_code != kNoResultExit) {
      e.retry = true;
      e.reason = "worker exited with code " + std::to_string(e.exit_code);
    }
  }
  return e;
}

/// The sweep's progress line (one rewritten line on a terminal, else a line
/// per finished case).
class Progress {
 public:
  Progress(bool on, std::size_t total) : line_("sweep", on), total_(total) {}
  void update(std::size_t done, std::size_t failed, std::size_t running, const std::string& note) {
    std::ostringstream text;
    text << done << "/" << total_ << " done, " << failed << " failed, " << running << " running";
    if (line_.drawn()) {
      line_.update(text.str(), done, total_);
    } else if (!note.empty()) {
      line_.note(line_.text(text.str(), done, total_) + " (" + note + ")");
    }
  }
  void finish() { line_.finish(); }

 private:
  ProgressLine line_;
  std::size_t total_;
};

}  // namespace

std::string_view to_string(SweepStatus status) {
  switch (status) {
    case SweepStatus::kComplete:
      return "complete";
    case SweepStatus::kDryRun:
      return "dry_run";
  }
  return "unknown";
}

void SweepOptions::validate() const {
  if (output_dir.empty()) throw InputError("--out: an output folder is required");
  if (ranks < 1 || rank < 0 || rank >= ranks) throw InputError("sweep: rank outside [0, ranks)");
  if (!(case_time_limit >= 0.0) || !std::isfinite(case_time_limit)) {
    throw InputError("--case-time-limit: must be a number of seconds > 0");
  }
  if (!run_command) throw InputError("sweep: no command runner");
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  if (jobs > kJobsPerCore * cores) {
    throw InputError("--jobs " + std::to_string(jobs) + ": at most " +
                     std::to_string(kJobsPerCore) + " worker processes per core, " +
                     std::to_string(kJobsPerCore * cores) + " on this machine's " +
                     std::to_string(cores) + " cores");
  }
}

std::string SweepResult::brief_report() const {
  std::ostringstream out;
  out << "sweep " << to_string(status) << ": " << cases << " cases";
  if (mine != cases) out << " (" << mine << " on this rank)";
  out << ", " << skipped << " already done, " << ran << " ran: " << ok << " ok, " << no_result
      << " without a result (exit code 2), " << errors << " input errors, " << failed << " failed; "
      << retries << " retries; " << seconds << " s";
  return out.str();
}

std::vector<Json> read_sweep_records(const fs::path& dir) {
  std::vector<Json> all;
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("results", 0) == 0 && entry.path().extension() == ".jsonl") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  std::map<std::string, std::size_t> position;
  for (const fs::path& file : files) {
    for (Json& record : read_records_file(file, false)) {
      const std::string id = record.at("case_id").get<std::string>();
      if (auto it = position.find(id); it != position.end()) {
        all[it->second] = std::move(record);
      } else {
        position[id] = all.size();
        all.push_back(std::move(record));
      }
    }
  }
  return all;
}

namespace {

/// A sweep's cases run on worker processes: this rank's queue (or the dealer's cases),
/// the running workers, and each ended case's record appended to results.jsonl.
class SweepExecution {
 public:
  SweepExecution(const SweepConfig& config, const SweepOptions& options, double limit,
                 const std::vector<PreparedCase>& prepared, std::vector<std::size_t> queue,
                 std::size_t mine, SweepResult& result)
      : config_(config),
        options_(options),
        limit_(limit),
        cases_dir_(fs::path(options.output_dir) / "cases"),
        prepared_(prepared),
        result_(result),
        queue_(std::move(queue)),
        dealer_(options.dealer),
        dealt_out_(dealer_ == nullptr),
        writer_(fs::path(options.output_dir) / results_file_name(options.rank)),
        jobs_(options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency())),
        host_(host_name()),
        progress_(options.progress, mine),
        finished_(result.skipped) {
    if (dealer_ != nullptr) {
      dealer_->deal(std::move(queue_));  // on rank 0; queue now holds only this rank's retries
      queue_.clear();
    }
    std::reverse(queue_.begin(), queue_.end());  // pop_back() takes them in design order
    std::cout.flush();
    std::cerr.flush();
  }

  /// Until every case of this rank (and, dealing, every rank's) has ended.
  void run() {
    const bool serving = dealer_ != nullptr && dealer_->deals();
    while (!queue_.empty() || !running_.empty() || !dealt_out_ ||
           (serving && !dealer_->served_all())) {
      fill_slots();
      // The dealer wakes often enough that a rank asking for a case waits about a
      // millisecond.
      const bool answering = serving && !dealer_->served_all();
      if (running_.empty() && queue_.empty() && dealt_out_ && !answering) break;  // none left
      for (const auto& [w, wait_status, timed_out] : reap(answering))
        conclude(w, wait_status, timed_out);
      if (serving) dealer_->serve();
    }
    progress_.finish();
  }

 private:
  // The dealer's progress line counts the other ranks' cases as they report them.
  std::size_t everyone_finished() const {
    return dealer_ != nullptr ? finished_ + dealer_->finished_elsewhere() : finished_;
  }
  std::size_t everyone_failed() const {
    return dealer_ != nullptr ? result_.failed + dealer_->failed_elsewhere() : result_.failed;
  }

  /// Starts cases (retries first, then the queue or the dealer's next) up to `jobs` workers.
  void fill_slots() {
    while (running_.size() < jobs_) {
      if (!queue_.empty()) {
        launch(queue_.back());
        queue_.pop_back();
      } else if (!dealt_out_) {
        const std::optional<std::size_t> next = dealer_->next(finished_, result_.failed);
        if (!next) {
          dealt_out_ = true;
          break;
        }
        launch(*next);
      } else {
        break;
      }
    }
  }

  /// A worker process for case `index` in its own process group, its output in the case's
  /// folder; the pipe's read end tells when it exits.
  void launch(std::size_t index) {
    const SweepCase& c = config_.cases[index];
    const fs::path case_dir = cases_dir_ / c.id;
    std::error_code ec;
    fs::remove_all(case_dir, ec);
    fs::create_directories(case_dir, ec);
    if (ec) throw Error("cannot create " + case_dir.string());
    for (const auto& [name, text] : prepared_[index].files) write_text_file(case_dir / name, text);
    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw Error("sweep: cannot create a pipe");
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw Error("sweep: cannot start a worker process (fork failed)");
    if (pid == 0) {
      ::close(pipe_fds[0]);
      ::setpgid(0, 0);
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a killed sweep takes its workers with it
      if (::getppid() != parent) ::_exit(137);
      const int out = ::open((case_dir / "stdout.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = ::open((case_dir / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out < 0 || err < 0) ::_exit(kInputErrorExit);
      ::dup2(out, 1);
      ::dup2(err, 2);
      const int code = run_case(config_, c, prepared_[index], options_);
      std::cout.flush();
      std::cerr.flush();
      std::fflush(nullptr);
      ::_exit(code);
    }
    ::setpgid(pid, pid);
    ::close(pipe_fds[1]);
    Worker w;
    w.pid = pid;
    w.done_fd = pipe_fds[0];
    w.case_index = index;
    w.attempt = ++attempts_[index];
    w.start = Clock::now();
    w.deadline = w.start +
                 std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit_));
    running_.push_back(w);
  }

  /// Waits for a worker to end (or a deadline, or the dealer's next tick); the workers that
  /// ended (killed at their deadline: timed out), reaped, with their wait status.
  std::vector<std::tuple<Worker, int, bool>> reap(bool answering) {
    auto wait_until =
        Clock::now() + (answering ? std::chrono::milliseconds(1) : std::chrono::milliseconds(1000));
    std::vector<pollfd> fds;
    for (const Worker& w : running_) {
      fds.push_back({w.done_fd, POLLIN, 0});
      wait_until = std::min(wait_until, w.deadline);
    }
    const auto wait_ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(wait_until - Clock::now()).count();
    ::poll(fds.data(), fds.size(), static_cast<int>(std::max<long long>(0, wait_ms) + 1));
    std::vector<Worker> still;
    std::vector<std::tuple<Worker, int, bool>> ended_workers;
    const auto now = Clock::now();
    for (std::size_t k = 0; k < running_.size(); ++k) {
      const Worker& w = running_[k];
      bool ended = false, timed_out = false;
      if (fds[k].revents != 0) {
        char sink[256];
        ended = ::read(w.done_fd, sink, sizeof sink) <= 0;
      }
      if (!ended && now >= w.deadline) {
        ::kill(-w.pid, SIGKILL);
        ended = timed_out = true;
      }
      if (!ended) {
        still.push_back(w);
        continue;
      }
      int wait_status = 0;
      while (::waitpid(w.pid, &wait_status, 0) < 0 && errno == EINTR) {
      }
      if (!timed_out) ::kill(-w.pid, SIGKILL);  // anything the worker left running
      ::close(w.done_fd);
      ended_workers.emplace_back(w, wait_status, timed_out);
    }
    running_ = std::move(still);
    return ended_workers;
  }

  /// An ended worker: retried (crashed or hung, attempts left) or recorded.
  void conclude(const Worker& w, int wait_status, bool timed_out) {
    const SweepCase& c = config_.cases[w.case_index];
    const Ending ending = ending_of(wait_status, timed_out, limit_);
    if (ending.retry && w.attempt <= config_.retries) {
      ++result_.retries;
      queue_.push_back(w.case_index);  // next, before the cases not yet started
      progress_.update(everyone_finished(), everyone_failed(), running_.size(),
                       c.id + " retried: " + ending.reason);
      return;
    }
    ++result_.ran;
    const Json record = record_of(w, ending);
    writer_.append(record);
    ++finished_;
    progress_.update(everyone_finished(), everyone_failed(), running_.size(),
                     c.id + " " + record.at("status").get<std::string>());
  }

  /// The case's record (status, reason, key figures, timing), counted in the result.
  Json record_of(const Worker& w, const Ending& ending) {
    const SweepCase& c = config_.cases[w.case_index];
    const fs::path case_dir = cases_dir_ / c.id;
    Json record = Json::object();
    record["case_id"] = c.id;
    record["index"] = c.index;
    record["job"] = config_.job;
    record["parameters"] = c.parameters;
    const Json output = ending.retry ? Json::object() : job_output(case_dir / "stdout.txt");
    std::string status;
    if (ending.retry) {
      status = "failed";
      ++result_.failed;
    } else if (ending.exit_code == kInputErrorExit) {
      status = "error";
      ++result_.errors;
    } else if (ending.exit_code == 0 && output.empty()) {
      // Exit 0 without the job's JSON result (a `--help` among its options printed the
      // usage instead): nothing to record as a result.
      status = "no_result";
      ++result_.no_result;
    } else {
      status = output.contains("status") && output.at("status").is_string()
                   ? output.at("status").get<std::string>()
                   : (ending.exit_code == 0 ? "ok" : "no_result");
      ++(ending.exit_code == 0 ? result_.ok : result_.no_result);
    }
    record["status"] = status;
    record["reason"] = ending.retry                          ? ending.reason
                       : ending.exit_code == kInputErrorExit ? first_line(case_dir / "stderr.txt")
                       : ending.exit_code == 0 && output.empty()
                           ? std::string("the job exited 0 without a JSON result on its stdout")
                           : std::string();
    record["exit_code"] = ending.exit_code;
    record["figures"] = key_figures(output);
    record["seconds"] = std::chrono::duration<double>(Clock::now() - w.start).count();
    record["attempts"] = w.attempt;
    record["host"] = host_;
    record["rank"] = options_.rank;
    return record;
  }

  const SweepConfig& config_;
  const SweepOptions& options_;
  double limit_;
  fs::path cases_dir_;
  const std::vector<PreparedCase>& prepared_;
  SweepResult& result_;
  std::vector<std::size_t> queue_;
  CaseDealer* dealer_;
  bool dealt_out_;  ///< no more cases to ask the dealer for
  RecordWriter writer_;
  std::size_t jobs_;
  std::string host_;
  std::map<std::size_t, int> attempts_;
  std::vector<Worker> running_;
  Progress progress_;
  std::size_t finished_;
};

/// Creates and locks the output folder (every rank its own lock; all must agree), repairs
/// this rank's results file, and returns the ids of the cases already recorded.
std::set<std::string> open_output(const SweepOptions& options, std::optional<SweepLock>& lock) {
  const fs::path dir = options.output_dir;
  std::error_code ec;
  fs::create_directories(dir / "cases", ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError("--out: cannot create the folder " + dir.string());
  }
  std::string lock_error;
  try {
    lock.emplace(dir, options.rank);
  } catch (const InputError& e) {
    lock_error = e.what();
  }
  const bool everyone =
      options.all_ranks_agree ? options.all_ranks_agree(lock.has_value()) : lock.has_value();
  if (!lock) throw InputError(lock_error);
  if (!everyone) throw InputError("--out: another rank could not lock " + dir.string());
  read_records_file(dir / results_file_name(options.rank), /*repair=*/true);
  std::set<std::string> done;
  for (const Json& record : read_sweep_records(dir))
    done.insert(record.at("case_id").get<std::string>());
  return done;
}

}  // namespace

SweepResult run_sweep(const SweepConfig& config, const SweepOptions& options) {
  options.validate();
  const auto started = Clock::now();
  const double limit =
      options.case_time_limit > 0.0 ? options.case_time_limit : config.case_time_limit;
  const fs::path cases_dir = fs::path(options.output_dir) / "cases";

  // Everything a case needs is resolved and checked before the first runs.
  std::vector<std::size_t> mine;
  std::vector<PreparedCase> prepared(config.cases.size());
  for (const SweepCase& c : config.cases) {
    prepared[c.index] = prepare_case(config, c, cases_dir / c.id, options.check_vehicle);
    if (options.check_command) {
      for (const auto& command : prepared[c.index].commands) options.check_command(command);
    }
    const bool static_share =
        static_cast<int>(c.index % static_cast<std::size_t>(options.ranks)) == options.rank;
    if (options.dealer != nullptr ? options.dealer->deals() : static_share) {
      mine.push_back(c.index);
    }
  }
  SweepResult result;
  result.cases = config.cases.size();
  result.mine = mine.size();
  if (options.dry_run) {
    result.status = SweepStatus::kDryRun;
    for (std::size_t i : mine) {
      result.dry_run_lines.push_back(config.cases[i].id + "  " + config.cases[i].parameters.dump());
    }
    return result;
  }

  std::optional<SweepLock> lock;
  const std::set<std::string> done = open_output(options, lock);
  std::vector<std::size_t> queue;
  for (std::size_t i : mine) {
    if (done.count(config.cases[i].id) != 0) {
      ++result.skipped;
    } else {
      queue.push_back(i);
    }
  }
  SweepExecution(config, options, limit, prepared, std::move(queue), mine.size(), result).run();
  if (options.dealer != nullptr) result.mine = result.skipped + result.ran;
  result.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return result;
}

}  // namespace talus
