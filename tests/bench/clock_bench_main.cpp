/// climbsim-bench-clock: lockstep steps per second with 1, 3 and 5 participants that do
/// no work, against the raw Fast DDS round trip between two processes, in the same run
/// (tests/bench, `./deploy/climbsim bench clock`).
///
/// Everything runs as real, separate processes: the clock and climbsim-test-participant
/// for the lockstep, climbsim-bench-pingpong (ping and pong) for the round trip. Every run
/// gets its own domain id from --domain-first..--domain-last. The step rate comes from the
/// clock's own final report (steps and wall seconds of the running phase, discovery and
/// arming excluded). The runs are repeated --repeat times, interleaved (round trip, then
/// each participant count), and the median of the repetitions is reported:
///
///   bench: clock: participants=N steps_per_s=.. step_us=.. rtt_us=.. ratio=..
///   bench: clock: rtt_us_median=.. rtt_us_p99=.. ratio_1=.. ratio_3=.. ratio_5=.. target=2.0 met=yes|no
///
/// ratio = step time / median round trip. The ratio is reported, not asserted: the exit
/// code is non-zero only if a run fails.
///
/// Unless --no-fanout, each repetition also measures the fan-out round trip to N pong
/// processes for every N > 1 measured (one ping answered by N echoes: the grant to N
/// participants and their N dones without the lockstep runtime), reported as
/// rtt_fanout_us and vs_fanout = step time / fan-out round trip. On a machine with fewer
/// cores than processes this, not the 1:1 round trip, is the transport's limit of a step.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "climbsim/domain_lease.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/process.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Options {
  fs::path bin_dir;
  fs::path out_json;
  fs::path log_dir;
  std::vector<int> participants{1, 3, 5};
  std::uint64_t steps = 3000;
  double step_ms = 1.0;
  std::string reads = "none";  ///< none: nobody reads; ring: p_i reads p_(i+1)
  int repeat = 3;
  int round_trips = 5000;
  int warmup = 500;
  int domain_first = 200;
  int domain_last = 230;
  double target = 2.0;
  double run_timeout_s = 300.0;
  bool fanout = true;
};

/// A benchmark run that did not complete; the message names the log to read.
struct RunFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Hands out the domain ids of the range in turn, each held with a DomainLease (the
/// machine-wide locks the tests and runs use) for as long as its run lasts: consecutive
/// runs never share a domain, and neither do concurrent benchmarks.
class Domains {
 public:
  Domains(int first, int last) : first_(first), last_(last), next_(first) {}
  climbsim::DomainLease lease() {
    for (int tried = 0; tried <= last_ - first_; ++tried) {
      const int id = next_;
      next_ = next_ >= last_ ? first_ : next_ + 1;
      try {
        return climbsim::DomainLease(id, id);
      } catch (const std::runtime_error&) {
        // taken by another run on this machine: try the next one
      }
    }
    throw RunFailed("no free DDS domain id in " + std::to_string(first_) + ".." + std::to_string(last_) +
                    " (see /tmp/climbsim-domains)");
  }

 private:
  int first_, last_, next_;
};

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string lastLines(const fs::path& path, std::size_t n) {
  std::istringstream in(readFile(path));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  std::string out;
  for (std::size_t i = lines.size() > n ? lines.size() - n : 0; i < lines.size(); ++i) {
    out += "    " + lines[i] + "\n";
  }
  return out;
}

/// A child whose output goes to a fresh log file.
struct Child {
  std::string what;
  fs::path log;
  climbsim::ChildProcess process;
};

Child start(const std::string& what, std::vector<std::string> argv, const fs::path& log) {
  fs::remove(log);
  climbsim::ProcessSpec spec;
  spec.argv = std::move(argv);
  spec.output_file = log.string();
  return Child{what, log, climbsim::ChildProcess(spec)};
}

/// Kills a child that did not end within `timeout` and throws RunFailed naming it.
[[noreturn]] void failStuck(Child& child, std::chrono::milliseconds timeout) {
  child.process.signal(SIGKILL);
  child.process.waitFor(std::chrono::seconds(5));
  throw RunFailed(child.what + " did not end within " + std::to_string(timeout.count() / 1000) + " s; log " +
                  child.log.string() + ":\n" + lastLines(child.log, 10));
}

/// Waits for the child to end with exit code 0; throws RunFailed otherwise (the
/// remaining children are killed by their destructors).
void expectSuccess(Child& child, std::chrono::milliseconds timeout) {
  const auto code = child.process.waitFor(timeout);
  if (!code) {
    failStuck(child, timeout);
  }
  if (*code != 0) {
    throw RunFailed(child.what + " exited with " + std::to_string(*code) + "; log " + child.log.string() + ":\n" +
                    lastLines(child.log, 10));
  }
}

/// Waits for `main` to end while watching `others`: a helper that fails early ends the run
/// at once instead of after the main process's own timeout. Then expects success of all.
void expectRun(Child& main, std::vector<Child>& others, std::chrono::milliseconds timeout,
               std::chrono::milliseconds others_timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!main.process.poll() && std::chrono::steady_clock::now() < deadline) {
    for (auto& other : others) {
      const auto code = other.process.poll();
      if (code && *code != 0) {
        expectSuccess(other, std::chrono::milliseconds(0));  // throws with its log
      }
    }
    // The driver's own polling period; it is not part of what is measured.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!main.process.poll()) {
    failStuck(main, timeout);
  }
  expectSuccess(main, std::chrono::milliseconds(0));
  for (auto& other : others) {
    expectSuccess(other, others_timeout);
  }
}

std::chrono::milliseconds ms(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(std::ceil(seconds * 1000.0)));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const auto n = v.size();
  return n == 0 ? 0.0 : (n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// ------------------------------------------------------------------ round trip

struct RttRun {
  int domain = 0;
  std::map<std::string, double> values;  ///< n, rtt_us_median, rtt_us_p99, ...
};

RttRun runPingPong(const Options& opt, int pongs, int domain, const std::string& tag) {
  const std::string exe = (opt.bin_dir / "climbsim-bench-pingpong").string();
  const std::string d = std::to_string(domain);
  std::vector<Child> pong;
  pong.reserve(static_cast<std::size_t>(pongs));
  for (int i = 1; i <= pongs; ++i) {
    const std::string name = "pong" + std::to_string(i);
    pong.push_back(start("pingpong " + name + " (domain " + d + ")",
                         {exe, "--role", "pong", "--name", name, "--domain", d},
                         opt.log_dir / (tag + "-" + name + ".log")));
  }
  auto ping = start("pingpong ping (domain " + d + ")",
                    {exe, "--role", "ping", "--pongs", std::to_string(pongs), "--domain", d, "--round-trips",
                     std::to_string(opt.round_trips), "--warmup", std::to_string(opt.warmup)},
                    opt.log_dir / (tag + "-ping.log"));
  expectRun(ping, pong, ms(opt.run_timeout_s), ms(10.0));

  RttRun run;
  run.domain = domain;
  std::istringstream text(readFile(ping.log));
  for (std::string line; std::getline(text, line);) {
    if (line.rfind("pingpong:", 0) != 0) {
      continue;
    }
    std::istringstream fields(line.substr(9));
    for (std::string field; fields >> field;) {
      const auto eq = field.find('=');
      if (eq == std::string::npos) {
        continue;
      }
      const std::string value = field.substr(eq + 1);
      char* end = nullptr;
      const double number = std::strtod(value.c_str(), &end);
      if (!value.empty() && end != nullptr && *end == '\0') {  // numbers only (not profile=...)
        run.values[field.substr(0, eq)] = number;
      }
    }
  }
  if (run.values.count("rtt_us_median") == 0 || run.values.count("rtt_us_p99") == 0) {
    throw RunFailed("ping printed no 'pingpong:' result line; log " + ping.log.string());
  }
  return run;
}

// ------------------------------------------------------------------ lockstep

struct StepRun {
  int domain = 0;
  std::uint64_t steps = 0;
  double wall_s = 0.0;
  double steps_per_s() const { return static_cast<double>(steps) / wall_s; }
};

StepRun runLockstep(const Options& opt, int participants, int domain, const std::string& tag) {
  const std::string d = std::to_string(domain);
  std::vector<std::string> names;
  for (int i = 1; i <= participants; ++i) {
    names.push_back("p" + std::to_string(i));
  }
  std::string roster;
  for (const auto& n : names) {
    roster += (roster.empty() ? "" : ",") + n;
  }
  std::vector<Child> children;
  children.reserve(names.size());
  for (int i = 0; i < participants; ++i) {
    std::vector<std::string> argv{(opt.bin_dir / "climbsim-test-participant").string(),
                                  "--name", names[i], "--period", "1", "--domain", d};
    if (opt.reads == "ring" && participants > 1) {
      argv.push_back("--reads");
      argv.push_back(names[(i + 1) % participants]);
    } else {
      // Participants that do no work: nothing read, nothing published but the protocol.
      argv.push_back("--no-output");
    }
    children.push_back(start("participant " + names[i] + " (domain " + d + ")", argv,
                             opt.log_dir / (tag + "-" + names[i] + ".log")));
  }
  std::ostringstream step_ms;
  step_ms << opt.step_ms;
  auto clock = start("clock (domain " + d + ")",
                     {(opt.bin_dir / "climbsim-clock").string(), "--roster", roster, "--steps",
                      std::to_string(opt.steps), "--step-ms", step_ms.str(), "--rtf", "0", "--domain", d,
                      "--start-timeout-s", "60"},
                     opt.log_dir / (tag + "-clock.log"));
  expectRun(clock, children, ms(opt.run_timeout_s), ms(15.0));

  // e.g. "end of run after 3000 steps: 3000 steps, 3.000 s simulated in 0.741 s wall (4.05x real time)"
  static const std::regex report(R"(: (\d+) steps, [0-9.]+ s simulated in ([0-9.]+) s wall)");
  const std::string text = readFile(clock.log);
  std::smatch m;
  if (!std::regex_search(text, m, report)) {
    throw RunFailed("the clock's log has no end-of-run report; log " + clock.log.string());
  }
  StepRun run;
  run.domain = domain;
  run.steps = std::stoull(m[1].str());
  run.wall_s = std::stod(m[2].str());
  if (run.steps == 0 || !(run.wall_s > 0.0)) {
    throw RunFailed("the clock reported " + m[0].str() + "; log " + clock.log.string());
  }
  return run;
}

std::string fmt(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

fs::path selfDir() {
  std::error_code ec;
  const auto exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::current_path() : exe.parent_path();
}

int run(const Options& opt) {
  fs::create_directories(opt.log_dir);
  if (!opt.out_json.empty()) {
    fs::create_directories(opt.out_json.parent_path().empty() ? fs::path(".") : opt.out_json.parent_path());
    fs::remove(opt.out_json);  // a failed run must not leave the last good figures behind
  }
  Domains domains(opt.domain_first, opt.domain_last);
  std::vector<RttRun> rtt_runs;
  std::map<int, std::vector<RttRun>> fanout_runs;  ///< by number of pongs
  std::map<int, std::vector<StepRun>> step_runs;
  for (int rep = 1; rep <= opt.repeat; ++rep) {
    const std::string r = "r" + std::to_string(rep);
    auto rtt = runPingPong(opt, 1, domains.lease().id(), r + "-pingpong");
    std::cerr << "bench-clock: repetition " << rep << ": round trip median " << fmt(rtt.values["rtt_us_median"], 1)
              << " us, p99 " << fmt(rtt.values["rtt_us_p99"], 1) << " us (domain " << rtt.domain << ")\n";
    rtt_runs.push_back(rtt);
    fanout_runs[1].push_back(rtt);
    for (int n : opt.participants) {
      if (!opt.fanout || n < 2 || fanout_runs[n].size() == static_cast<std::size_t>(rep)) {
        continue;
      }
      auto f = runPingPong(opt, n, domains.lease().id(), r + "-fanout" + std::to_string(n));
      std::cerr << "bench-clock: repetition " << rep << ": fan-out round trip to " << n << " pongs median "
                << fmt(f.values["rtt_us_median"], 1) << " us, p99 " << fmt(f.values["rtt_us_p99"], 1)
                << " us (domain " << f.domain << ")\n";
      fanout_runs[n].push_back(f);
    }
    for (int n : opt.participants) {
      auto s = runLockstep(opt, n, domains.lease().id(), r + "-lockstep" + std::to_string(n));
      std::cerr << "bench-clock: repetition " << rep << ": " << n << " participant(s): " << s.steps << " steps in "
                << fmt(s.wall_s, 3) << " s = " << fmt(s.steps_per_s(), 0) << " steps/s (domain " << s.domain
                << ")\n";
      step_runs[n].push_back(s);
    }
  }

  auto rttMedianOf = [](std::vector<RttRun>& runs, const std::string& key) {
    std::vector<double> v;
    for (auto& r : runs) {
      v.push_back(r.values[key]);
    }
    return median(v);
  };
  auto runsJson = [](std::vector<RttRun>& runs) {
    json out = json::array();
    for (auto& r : runs) {
      json one = {{"domain", r.domain}};
      for (const auto& [k, v] : r.values) {
        one[k] = v;
      }
      out.push_back(one);
    }
    return out;
  };
  const double rtt_us = rttMedianOf(rtt_runs, "rtt_us_median");
  const double rtt_p99 = rttMedianOf(rtt_runs, "rtt_us_p99");

  json doc;
  doc["name"] = "clock";
  doc["config"] = {{"steps", opt.steps},        {"step_ms", opt.step_ms},         {"rtf", 0},
                   {"period", 1},               {"work_us", 0},                   {"reads", opt.reads}, {"outputs", opt.reads == "ring" ? "one each" : "none"},
                   {"repeat", opt.repeat},      {"round_trips", opt.round_trips}, {"warmup", opt.warmup},
                   {"qos_profile", "climbsim.control"}, {"cpus", static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN))}};
  doc["pingpong"] = {{"rtt_us_median", rtt_us}, {"rtt_us_p99", rtt_p99}, {"runs", runsJson(rtt_runs)}};
  doc["fanout"] = json::array();
  for (auto& [pongs, runs] : fanout_runs) {
    if (pongs > 1) {
      doc["fanout"].push_back({{"pongs", pongs},
                               {"rtt_us_median", rttMedianOf(runs, "rtt_us_median")},
                               {"rtt_us_p99", rttMedianOf(runs, "rtt_us_p99")},
                               {"runs", runsJson(runs)}});
    }
  }
  doc["lockstep"] = json::array();

  std::map<int, double> ratios;
  for (int n : opt.participants) {
    std::vector<double> rates;
    json runs = json::array();
    for (const auto& s : step_runs[n]) {
      rates.push_back(s.steps_per_s());
      runs.push_back({{"domain", s.domain}, {"steps", s.steps}, {"wall_s", s.wall_s}, {"steps_per_s", s.steps_per_s()}});
    }
    const double steps_per_s = median(rates);
    const double step_us = 1e6 / steps_per_s;
    const double ratio = step_us / rtt_us;
    ratios[n] = ratio;
    std::cout << "bench: clock: participants=" << n << " steps_per_s=" << fmt(steps_per_s, 0)
              << " step_us=" << fmt(step_us, 1) << " rtt_us=" << fmt(rtt_us, 1) << " ratio=" << fmt(ratio, 2);
    json entry = {{"participants", n}, {"steps_per_s", steps_per_s}, {"step_us", step_us},
                  {"rtt_us", rtt_us},  {"ratio", ratio},             {"runs", runs}};
    if (!fanout_runs[n].empty()) {
      const double fan_us = rttMedianOf(fanout_runs[n], "rtt_us_median");
      std::cout << " rtt_fanout_us=" << fmt(fan_us, 1) << " vs_fanout=" << fmt(step_us / fan_us, 2);
      entry["rtt_fanout_us"] = fan_us;
      entry["vs_fanout"] = step_us / fan_us;
    }
    std::cout << std::endl;
    doc["lockstep"].push_back(entry);
    doc["ratio_" + std::to_string(n)] = ratio;
  }

  std::ostringstream summary;
  summary << "bench: clock: rtt_us_median=" << fmt(rtt_us, 1) << " rtt_us_p99=" << fmt(rtt_p99, 1);
  for (const auto& [n, ratio] : ratios) {
    summary << " ratio_" << n << "=" << fmt(ratio, 2);
  }
  doc["target"] = opt.target;
  if (ratios.count(3) != 0) {
    const bool met = ratios[3] <= opt.target;
    summary << " target=" << fmt(opt.target, 1) << " met=" << (met ? "yes" : "no");
    doc["met"] = met;
  } else {
    summary << " target=" << fmt(opt.target, 1) << " met=n/a";
    doc["met"] = nullptr;
  }
  std::cout << summary.str() << std::endl;

  if (!opt.out_json.empty()) {
    std::ofstream out(opt.out_json);
    out << doc.dump(2) << "\n";
    if (!out) {
      throw std::runtime_error("cannot write '" + opt.out_json.string() + "'");
    }
  }
  return climbsim::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-clock: lockstep steps/s with 1, 3, 5 idle participants vs. the raw DDS round trip"};
  Options opt;
  std::string bin_dir, out_json, log_dir;
  app.add_option("--bin-dir", bin_dir, "where climbsim-clock, -test-participant, -bench-pingpong are (default: ours)");
  app.add_option("--out", out_json, "write the results as JSON here (e.g. build/bench/clock.json)");
  app.add_option("--log-dir", log_dir, "logs of every child process (default: next to --out, or /tmp)");
  app.add_option("--participants", opt.participants, "participant counts to measure")->delimiter(',');
  app.add_option("--steps", opt.steps, "clock steps per lockstep run")->check(CLI::PositiveNumber);
  app.add_option("--step-ms", opt.step_ms, "simulated step length [ms] (RTF 0: no effect on speed)");
  app.add_option("--reads", opt.reads, "none: participants read nobody; ring: p_i reads p_(i+1)")
      ->check(CLI::IsMember({"none", "ring"}));
  app.add_option("--repeat", opt.repeat, "repetitions (median reported)")->check(CLI::PositiveNumber);
  app.add_option("--round-trips", opt.round_trips, "measured ping-pong round trips per repetition")
      ->check(CLI::PositiveNumber);
  app.add_option("--warmup", opt.warmup, "ping-pong warm-up round trips")->check(CLI::PositiveNumber);
  app.add_option("--domain-first", opt.domain_first, "first DDS domain id for the runs")->check(CLI::Range(0, 232));
  app.add_option("--domain-last", opt.domain_last, "last DDS domain id for the runs")->check(CLI::Range(0, 232));
  app.add_option("--target", opt.target, "target ratio with 3 participants (reported, not asserted)");
  app.add_option("--run-timeout-s", opt.run_timeout_s, "limit for one run [s]");
  app.add_flag("!--no-fanout", opt.fanout, "skip the fan-out round trips to N pongs");
  try {
    app.parse(argc, argv);
    if (opt.domain_last < opt.domain_first) {
      throw CLI::ValidationError("--domain-last", "must be >= --domain-first");
    }
    for (int n : opt.participants) {
      if (n < 1) {
        throw CLI::ValidationError("--participants", "every count must be >= 1");
      }
    }
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? climbsim::kExitOk : climbsim::kExitConfig;
  }
  opt.bin_dir = bin_dir.empty() ? selfDir() : fs::path(bin_dir);
  opt.out_json = out_json;
  opt.log_dir = !log_dir.empty() ? fs::path(log_dir)
                : !out_json.empty() ? opt.out_json.parent_path() / "clock-logs"
                                    : fs::temp_directory_path() / ("climbsim-bench-clock-" + std::to_string(getpid()));
  try {
    return run(opt);
  } catch (const RunFailed& e) {
    std::cerr << "bench-clock: error: " << e.what() << std::flush;
    std::cout << "bench: clock: failed" << std::endl;
    return climbsim::kExitFailed;
  } catch (const std::exception& e) {
    std::cerr << "bench-clock: error: " << e.what() << std::endl;
    std::cout << "bench: clock: failed" << std::endl;
    return climbsim::kExitFailed;
  }
}
