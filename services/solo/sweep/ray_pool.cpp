#include "ray_pool.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"

namespace climbsim::sweep {

RayPool::RayPool(const std::vector<VariantJob>& jobs, const RayOptions& options) {
  namespace fs = std::filesystem;
  if (::access(options.driver.c_str(), X_OK) != 0) {
    throw ConfigError("--ray: " + options.driver +
                      " is missing (the build's Python runtime, CLIMBSIM_PYTHON=ON, brings it and Ray)");
  }
  nlohmann::json request;
  request["address"] = options.address;
  request["out"] = fs::absolute(options.out_dir).string();
  request["cpus_per_variant"] = options.cpus_per_variant;
  request["root"] = options.root;
  request["needs"] = options.needs;
  request["address_file"] = options.address_file;
  for (const auto& job : jobs) {
    request["jobs"].push_back({{"index", job.variant.index}, {"dir", fs::absolute(job.dir).string()}, {"argv", job.argv}});
    open_.insert(job.variant.index);
  }
  char name[] = "/tmp/climbsim-ray-sweep-XXXXXX";
  const int fd = ::mkstemp(name);
  if (fd < 0) throw std::runtime_error("--ray: cannot make a request file in /tmp");
  ::close(fd);
  request_file_ = name;
  std::ofstream(request_file_) << request.dump();
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error("--ray: pipe() failed");
  read_fd_ = pipe_fds[0];
  ::fcntl(read_fd_, F_SETFL, ::fcntl(read_fd_, F_GETFL) | O_NONBLOCK);
  ::fcntl(read_fd_, F_SETFD, FD_CLOEXEC);
  ProcessSpec spec;
  spec.argv = {options.driver, request_file_};
  spec.output_fd = pipe_fds[1];
  driver_ = std::make_unique<ChildProcess>(spec);
  ::close(pipe_fds[1]);
  load_.queued = jobs.size();
}

RayPool::~RayPool() {
  driver_.reset();  // kills a driver still running
  if (read_fd_ >= 0) ::close(read_fd_);
  if (!request_file_.empty()) std::remove(request_file_.c_str());
}

std::vector<VariantEnd> RayPool::poll() {
  std::vector<VariantEnd> ended;
  if (driver_done_) return ended;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(read_fd_, buffer, sizeof buffer);
    if (n <= 0) break;
    partial_.append(buffer, static_cast<std::size_t>(n));
  }
  for (std::size_t nl; (nl = partial_.find('\n')) != std::string::npos;) {
    handle(partial_.substr(0, nl), ended);
    partial_.erase(0, nl + 1);
  }
  const auto code = driver_->poll();
  if (!code) return ended;
  for (ssize_t n; (n = ::read(read_fd_, buffer, sizeof buffer)) > 0;) partial_.append(buffer, static_cast<std::size_t>(n));
  for (std::size_t nl; (nl = partial_.find('\n')) != std::string::npos;) {
    handle(partial_.substr(0, nl), ended);
    partial_.erase(0, nl + 1);
  }
  driver_done_ = true;
  if (*code != kExitOk && !fatal_ && !stopping_) {
    fatal_ = "the Ray driver ended with exit code " + std::to_string(*code) + " (its words are above)";
  }
  for (const std::size_t index : open_) {  // never ended: stopped, or not run for the reason above
    VariantEnd end;
    end.index = index;
    end.stopped = true;
    ended.push_back(end);
  }
  open_.clear();
  load_ = {};
  return ended;
}

void RayPool::handle(const std::string& line, std::vector<VariantEnd>& ended) {
  const auto event = line.empty() || line[0] != '{' ? nlohmann::json() : nlohmann::json::parse(line, nullptr, false);
  if (!event.is_object()) {
    std::fprintf(stderr, "%s\n", line.c_str());  // the driver's own words
    return;
  }
  if (event.contains("load")) {
    load_.running = event["load"].value("running", std::size_t{0});
    load_.queued = event["load"].value("queued", std::size_t{0});
  } else if (event.contains("fatal")) {
    fatal_ = event["fatal"].get<std::string>();
  } else if (event.contains("ended") || event.contains("lost")) {
    VariantEnd end;
    end.index = event.contains("ended") ? event["ended"].get<std::size_t>() : event["lost"].get<std::size_t>();
    if (open_.erase(end.index) == 0) return;  // once only
    if (event.contains("ended")) {
      end.exit_code = event.value("exit_code", 1);
      end.wall_s = event.value("wall_s", 0.0);
      end.stopped = *end.exit_code == kExitStopped;
    } else {
      end.note = event.value("reason", std::string("lost"));
    }
    ended.push_back(end);
  }
}

void RayPool::stop() {
  if (!stopping_ && driver_ && !driver_done_) driver_->signal(SIGINT);
  stopping_ = true;
}

}  // namespace climbsim::sweep
