#include "supervisor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <spdlog/fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/process.hpp"
#include "line_splitter.hpp"
#include "viewer_port.hpp"

namespace climbsim::launcher {

namespace {
using Clock = std::chrono::steady_clock;

void bringForward(std::optional<Clock::time_point>& deadline, Clock::time_point when) {
  if (!deadline || when < *deadline) {
    deadline = when;
  }
}

std::string seconds(std::chrono::milliseconds duration) {
  return formatNumber(static_cast<double>(duration.count()) / 1000.0) + " s";
}

/// True if the process is stopped (state T: SIGSTOP, SIGTSTP; t: stopped by a debugger),
/// from /proc/<pid>/stat (Linux). A process of another host is its ssh client here: never.
bool isStopped(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  std::getline(in, text);
  const auto paren = text.rfind(')');  // the command name may hold spaces and parentheses
  if (paren == std::string::npos || paren + 2 >= text.size()) return false;
  const char state = text[paren + 2];
  return state == 'T' || state == 't';
}
}  // namespace

struct Supervisor::Managed {
  std::size_t index = 0;
  std::string name;
  bool observer = false;
  std::optional<std::chrono::steady_clock::time_point> stopped_since;
  bool stopped_reported = false;
  /// A stopped service is killed once the clock has ended the run (having seen it stopped: its
  /// Stop reason says so) or at this time, whichever comes first.
  std::optional<std::chrono::steady_clock::time_point> kill_stopped_at;
  std::optional<ChildProcess> child;
  int pipe_fd = -1;
  LineSplitter splitter;
  std::optional<int> exit_code;

  ~Managed() {
    if (pipe_fd >= 0) {
      ::close(pipe_fd);
    }
  }
};

Supervisor::Supervisor(LaunchPlan plan, RunPaths paths, RunState state, SupervisorOptions options,
                       SignalEvents& signals)
    : plan_(std::move(plan)),
      paths_(std::move(paths)),
      state_(std::move(state)),
      options_(std::move(options)),
      signals_(signals) {}

Supervisor::~Supervisor() = default;

void Supervisor::start() {
  std::vector<std::string> names;
  for (const auto& launch : plan_.processes) {
    names.push_back(launch.name);
  }
  output_ = std::make_unique<OutputRouter>(names, options_.to_terminal, options_.color);
  for (std::size_t i = 0; i < names.size(); ++i) {
    output_->addLogFile(i, paths_.logFile(names[i]));
    for (const auto& dir : options_.extra_log_dirs) {
      output_->addLogFile(i, (std::filesystem::path(dir) / (names[i] + ".log")).string());
    }
  }
  state_.processes.clear();
  saveState();  // `ps` must not show the processes of the previous run as this run's
  for (std::size_t i = 0; i < plan_.processes.size(); ++i) {
    const auto& launch = plan_.processes[i];
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
    }
    auto process = std::make_unique<Managed>();
    process->index = i;
    process->name = launch.name;
    process->observer = launch.observer;
    process->pipe_fd = fds[0];
    ProcessSpec spec;
    spec.argv = launch.argv;
    spec.env = launch.env;
    spec.output_fd = fds[1];
    spec.die_with_parent = true;
    try {
      std::optional<SignalEvents::InterruptShield> shield;
      if (options_.shield_interrupt) {
        shield.emplace();
      }
      process->child.emplace(spec);
    } catch (...) {
      ::close(fds[1]);
      throw;
    }
    ::close(fds[1]);
    ::fcntl(fds[0], F_SETFL, ::fcntl(fds[0], F_GETFL) | O_NONBLOCK);
    spdlog::debug("started {} (pid {}): {}", launch.name, process->child->pid(), fmt::join(launch.argv, " "));
    ProcessState entry;
    entry.name = launch.name;
    entry.pid = process->child->pid();
    entry.host = launch.host;
    state_.processes.push_back(entry);
    processes_.push_back(std::move(process));
  }
  saveState();
}

int Supervisor::wait() {
  if (!options_.progress_trace.empty()) {
    trace_ = std::make_unique<TraceTail>(options_.progress_trace);
    next_progress_ = Clock::now();
  }
  while (!everyoneEnded()) {
    pollOnce();
  }
  showProgress(true);
  // Every process has ended; what a grandchild may still hold open is cut off here.
  for (auto& process : processes_) {
    readOutput(*process, true);
  }
  const int code = exitCode();
  state_.exit_code = code;
  saveState();
  return code;
}

void Supervisor::pollOnce() {
  // Exits are checked before sleeping: a SIGCHLD that came meanwhile is still in the pipe.
  reapExits();
  checkStopped();
  applyDeadlines();
  if (everyoneEnded()) {
    return;
  }
  std::vector<pollfd> fds;
  std::vector<Managed*> owners;
  fds.push_back(pollfd{signals_.fd(), POLLIN, 0});
  owners.push_back(nullptr);
  for (auto& process : processes_) {
    if (process->pipe_fd >= 0) {
      fds.push_back(pollfd{process->pipe_fd, POLLIN, 0});
      owners.push_back(process.get());
    }
  }
  int timeout_ms = -1;
  auto now = Clock::now();
  if (trace_) {
    if (now >= next_progress_) {
      showProgress(false);
      now = Clock::now();
    }
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(next_progress_ - now).count();
    timeout_ms = static_cast<int>(std::max<long long>(0, left));
  }
  // Stopped processes give no event: look at them a few times a second.
  const auto stopped_check_ms = std::max<long long>(
      0, std::chrono::ceil<std::chrono::milliseconds>(next_stopped_check_ - now).count());
  timeout_ms = timeout_ms < 0 ? static_cast<int>(stopped_check_ms)
                              : std::min(timeout_ms, static_cast<int>(stopped_check_ms));
  for (const auto& deadline : {stop_clock_at_, term_at_, kill_at_}) {
    if (deadline) {
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(*deadline - now).count();
      const int left_ms = static_cast<int>(std::max<long long>(0, left));
      timeout_ms = timeout_ms < 0 ? left_ms : std::min(timeout_ms, left_ms);
    }
  }
  const int ready = ::poll(fds.data(), fds.size(), timeout_ms);
  if (ready < 0 && errno != EINTR) {
    throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
  }
  for (std::size_t i = 0; ready > 0 && i < fds.size(); ++i) {
    if (fds[i].revents == 0) {
      continue;
    }
    if (owners[i] == nullptr) {
      for (const int signal_number : signals_.drain()) {
        onStopRequest(signal_number);
      }
    } else {
      readOutput(*owners[i], false);
    }
  }
}

void Supervisor::readOutput(Managed& process, bool until_end) {
  if (process.pipe_fd < 0) {
    return;
  }
  const auto emit = [&](std::string_view line) {
    if (const auto dropped = run_summary::droppedSamplesIn(line)) dropped_[process.name] = *dropped;
    if (const auto wheel = run_summary::wheelOverNothingIn(line)) wheels_over_nothing_.push_back(*wheel);
    if (process.observer && viewer_address_.empty()) {
      if (const auto address = viewerAddressIn(line)) {
        viewer_address_ = *address;
        state_.viewer_url = viewer_address_;  // `ps RUN` shows it (a detached `up` printed none)
        saveState();
        output_->line(process.index, line);
        // The address it took (the default port may have been another run's): said once, as
        // the launcher's own line, also in a detached supervisor's log.
        spdlog::info("the viewer of '{}' is at {}", state_.name, viewer_address_);
        return;
      }
    }
    if (process.index == 0 && clock_failure_.empty()) {
      constexpr std::string_view kFailed = "run failed: ";
      if (const auto at = line.find(kFailed); at != std::string_view::npos) {
        clock_failure_ = std::string(line.substr(at + kFailed.size()));
      }
    }
    output_->line(process.index, line);
  };
  char buffer[64 * 1024];
  // One read per wake-up keeps a chatty process from starving the others; at the end,
  // read until the pipe is empty (bounded: a grandchild may still be writing).
  int reads_left = 64;
  do {
    const ssize_t got = ::read(process.pipe_fd, buffer, sizeof(buffer));
    if (got > 0) {
      process.splitter.feed(std::string_view(buffer, static_cast<std::size_t>(got)), emit);
      continue;
    }
    if (got < 0 && errno == EINTR) {
      continue;
    }
    if (got < 0 && errno == EAGAIN && !until_end) {
      return;
    }
    process.splitter.finish(emit);
    ::close(process.pipe_fd);
    process.pipe_fd = -1;
    return;
  } while (until_end && --reads_left > 0);
  if (until_end && process.pipe_fd >= 0) {
    process.splitter.finish(emit);
    ::close(process.pipe_fd);
    process.pipe_fd = -1;
  }
}

void Supervisor::reapExits() {
  // The clock's end first (it sets the deadlines for the others), then the services found
  // ended in this look, those a signal ended first (blameOrder).
  std::vector<Managed*> ended;
  std::vector<int> codes;
  for (auto& process : processes_) {
    if (!process->exit_code) {
      if (const auto code = process->child->poll()) {
        if (process->index == 0) {
          onExit(*process, *code);
          continue;
        }
        ended.push_back(process.get());
        codes.push_back(*code);
      }
    }
  }
  for (const std::size_t i : blameOrder(codes)) {
    onExit(*ended[i], codes[i]);
  }
}

void Supervisor::onExit(Managed& process, int code) {
  process.exit_code = code;
  state_.processes.at(process.index).exit_code = code;
  state_.processes.at(process.index).cpu_s = process.child->cpuSeconds();
  state_.processes.at(process.index).ctx_switches = process.child->contextSwitches();
  saveState();
  const auto now = Clock::now();
  if (process.index == 0) {
    if (code == kExitOk) {
      spdlog::info("the clock completed the run");
    } else if (code == kExitStopped) {
      spdlog::warn("the clock stopped the run on request (exit code {})", code);
    } else if (code == kExitFell) {
      spdlog::warn("the robot fell: the clock ended the run (exit code {})", code);
    } else {
      spdlog::error("the clock exited with code {}", code);
    }
    bringForward(term_at_, now + options_.grace);
    bringForward(kill_at_, now + options_.grace + options_.term_wait);
    return;
  }
  if (code != 0 && process.observer) {
    // An observer never gates a step (e.g. a second run's viewer finding its port taken).
    spdlog::warn("observer '{}' exited with code {}: the run goes on without it", process.name, code);
    return;
  }
  if (code != 0) {
    spdlog::error("service '{}' exited with code {}", process.name, code);
    if (!first_failure_) first_failure_ = run_summary::FailedProcess{process.name, code};
    if (!processes_.front()->exit_code && !stop_clock_at_) {
      stop_clock_reason_ = "'" + process.name + "' failed";
      bringForward(stop_clock_at_, now + options_.grace);
    }
  }
}

void Supervisor::checkStopped() {
  const auto now = Clock::now();
  for (auto& process : processes_) {
    if (process->kill_stopped_at && !process->exit_code &&
        (processes_.front()->exit_code || now >= *process->kill_stopped_at)) {
      // SIGTERM would stay pending while it is stopped: SIGKILL ends a stopped process.
      process->child->signal(SIGKILL);
      process->kill_stopped_at.reset();
    }
  }
  if (now < next_stopped_check_) return;
  next_stopped_check_ = now + std::chrono::milliseconds(250);
  for (auto& process : processes_) {
    if (process->exit_code || process->stopped_reported) continue;
    if (!isStopped(process->child->pid())) {
      process->stopped_since.reset();
      continue;
    }
    if (!process->stopped_since) process->stopped_since = now;
    if (now - *process->stopped_since < options_.stopped_limit) continue;
    process->stopped_reported = true;
    const bool is_clock = process->index == 0;
    spdlog::error("{} '{}' (pid {}) is stopped (SIGSTOP or a debugger): its process exists but does not run; "
                  "ending the run and killing it",
                  is_clock ? "the clock" : "service", process->name, process->child->pid());
    if (!first_failure_ && !is_clock) first_failure_ = run_summary::FailedProcess{process->name, 128 + SIGSTOP};
    if (stopped_note_.empty()) {
      stopped_note_ = std::string(": ") + (is_clock ? "the clock" : "service") + " '" + process->name + "' (pid " +
                      std::to_string(process->child->pid()) +
                      ") was stopped (SIGSTOP or a debugger): it existed but did not run, so the run ended and the "
                      "launcher killed it";
    }
    if (is_clock) {
      // SIGTERM would stay pending while it is stopped: SIGKILL ends a stopped process.
      process->child->signal(SIGKILL);
      // Nobody can stop the run in order: the services wait for grants that never come.
      signalRunning(SIGTERM, "the clock is stopped");
      bringForward(kill_at_, now + options_.term_wait);
    } else if (!processes_.front()->exit_code) {
      // The clock notices the stopped participant in /proc (after 1 s stopped) and fails the run
      // naming it, in its own words ("its process 123 is stopped"): it is killed only then, or
      // should the clock not notice, when the clock is asked to stop.
      stop_clock_reason_ = "'" + process->name + "' is stopped";
      bringForward(stop_clock_at_, now + std::chrono::milliseconds(1500));
      process->kill_stopped_at = now + std::chrono::milliseconds(1500);
    } else {
      process->child->signal(SIGKILL);
    }
  }
}

void Supervisor::onStopRequest(int signal_number) {
  ++stop_requests_;
  if (stop_requests_ > 1) {
    signalRunning(SIGKILL, std::string("another ") + ::strsignal(signal_number));
    return;
  }
  spdlog::warn("{}: stopping the run (again to kill every process at once)", ::strsignal(signal_number));
  stopTheClock("a stop was requested");
}

void Supervisor::stopTheClock(const std::string& why) {
  const auto now = Clock::now();
  auto& clock = *processes_.front();
  if (!clock.exit_code) {
    spdlog::info("asking the clock to stop the run ({})", why);
    clock.child->signal(SIGTERM);
  }
  bringForward(term_at_, now + options_.stop_wait);
  bringForward(kill_at_, now + options_.stop_wait + options_.term_wait);
}

void Supervisor::applyDeadlines() {
  const auto now = Clock::now();
  if (stop_clock_at_ && now >= *stop_clock_at_) {
    stop_clock_at_.reset();
    if (!processes_.front()->exit_code) {
      spdlog::warn("the clock still runs {} after {}", seconds(options_.grace), stop_clock_reason_);
      stopTheClock(stop_clock_reason_);
    }
  }
  if (term_at_ && now >= *term_at_) {
    term_at_.reset();
    signalRunning(SIGTERM, "they did not end in time");
  }
  if (kill_at_ && now >= *kill_at_) {
    kill_at_.reset();
    signalRunning(SIGKILL, "they did not end after SIGTERM");
  }
}

void Supervisor::signalRunning(int signal_number, const std::string& why) {
  std::vector<std::string> names;
  for (auto& process : processes_) {
    if (!process->exit_code) {
      process->child->signal(signal_number);
      names.push_back(process->name);
    }
  }
  if (!names.empty()) {
    spdlog::warn("sending {} to {} ({})", signal_number == SIGKILL ? "SIGKILL" : "SIGTERM", fmt::join(names, ", "),
                 why);
  }
}

bool Supervisor::everyoneEnded() const {
  return std::all_of(processes_.begin(), processes_.end(), [](const auto& p) { return p->exit_code.has_value(); });
}

std::vector<ProcessEnd> Supervisor::processEnds() const {
  std::vector<ProcessEnd> ends;
  for (const auto& process : processes_) {
    if (!process->observer) ends.push_back(ProcessEnd{process->name, process->exit_code});
  }
  return ends;
}

int Supervisor::exitCode() const { return runExitCode(processEnds()); }

std::string Supervisor::runStateText() const {
  const auto& clock = *processes_.front();
  std::size_t failed = 0;
  for (const auto& process : processes_) {
    // The clock's own code is told apart ("ended (clock exit 5)"); observers never fail a run.
    if (process->index != 0 && process->exit_code && *process->exit_code != 0 && !process->observer) ++failed;
  }
  std::string text;
  if (clock.exit_code) {
    text = *clock.exit_code == 0 ? "completed" : "ended (clock exit " + std::to_string(*clock.exit_code) + ")";
  } else if (stop_clock_at_ || term_at_ || stop_requests_ > 0) {
    text = "stopping";
  } else {
    text = first_row_ ? "running" : "starting";
  }
  if (failed > 0) text += ", " + std::to_string(failed) + " failed";
  return text;
}

void Supervisor::showProgress(bool final_word) {
  if (!trace_) return;
  const auto now = Clock::now();
  const auto sample = trace_->poll();
  if (sample && !first_row_) first_row_ = std::make_pair(now, sample->t_s);
  std::optional<double> rtf;
  if (sample && first_row_) {
    const double wall_s = std::chrono::duration<double>(now - first_row_->first).count();
    rate_.see(wall_s, sample->t_s);
    // Once the clock has ended the run, the rate up to its last row (not to now: the viewer of
    // `up` may keep the launcher waiting, and the run's rate is what the line reports).
    rtf = rate_.rate(wall_s, final_word || processes_.front()->exit_code.has_value());
  }
  if (final_word) {
    // The recorder's own figure when it wrote one: its steps over its wall time, exact, where
    // the rows seen at each poll are only as fine as the polls.
    std::ifstream in((std::filesystem::path(options_.progress_trace).parent_path() / "summary.json").string());
    const auto summary = nlohmann::json::parse(in, nullptr, false);
    if (summary.is_object() && summary.contains("realtime_factor") && summary["realtime_factor"].is_number() &&
        summary["realtime_factor"].get<double>() > 0.0) {
      rtf = summary["realtime_factor"].get<double>();
    }
  }
  std::optional<TraceSample> shown = sample;
  if (final_word && shown && processes_.front()->exit_code == kExitOk && options_.progress_duration_s > 0.0) {
    // The clock completed the run: it reached its end time (the last row is stamped one step
    // before it, which a short run would show as 50 %).
    shown->t_s = options_.progress_duration_s;
  }
  const std::string text = "climbsim: " + progressText(shown, options_.progress_duration_s, rtf, runStateText());
  if (options_.progress_live) {
    output_->status(text);
    if (final_word) output_->keepStatus();
    next_progress_ = now + std::chrono::milliseconds(500);
  } else {
    spdlog::info("{}", text.substr(std::string("climbsim: ").size()));
    next_progress_ = now + options_.progress_log_every;
  }
}

void Supervisor::saveState() {
  try {
    writeRunState(paths_.state_file, state_);
  } catch (const std::exception& e) {
    spdlog::warn("{}", e.what());
  }
}

}  // namespace climbsim::launcher
