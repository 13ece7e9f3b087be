/// climbsim-test-participant: a small lockstep participant for the integration tests,
/// the benchmarks and the `up` demo. It writes TestSample on "test/<name>" each due
/// step, reads the samples of the participants named by --reads, and records what it
/// read, one line per sample, so that two runs can be compared byte for byte.

#include <chrono>
#include <fstream>
#include <thread>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/names.hpp"
#include "testingPubSubTypes.h"

namespace {
/// FNV-1a, 64 bit: a deterministic digest of what a participant read.
std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ULL;
  }
  return hash;
}

void spinFor(std::chrono::microseconds work) {
  const auto until = std::chrono::steady_clock::now() + work;
  while (std::chrono::steady_clock::now() < until) {
  }
}
}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-test-participant: a lockstep participant for tests"};
  ParticipantOptions options;
  std::string reads;
  std::string reads_same_step;
  std::string record_file;
  std::int64_t work_us = 0;
  std::size_t payload = 0;
  std::int64_t fail_at = -1;
  std::int64_t hang_at = -1;
  bool no_output = false;
  options.addOptions(app);
  app.add_option("--reads", reads, "participants whose test/<name> topic this one reads, comma-separated");
  app.add_option("--reads-same-step", reads_same_step,
                 "participants read with lag 0: their sample of the same step (InputLag::kSameStep)");
  app.add_option("--record", record_file, "write what was read to this file");
  app.add_option("--work-us", work_us, "busy work per step [us]");
  app.add_option("--payload", payload, "doubles of payload per sample");
  app.add_option("--fail-at-step", fail_at, "throw at this step (failure tests)");
  app.add_option("--hang-at-step", hang_at, "stop answering at this step (watchdog tests)");
  app.add_flag("--no-output", no_output, "publish nothing: only the lockstep protocol (benchmarks)");
  return guardedMain(app, argc, argv, "test-participant", [&]() -> int {
    initLogging(options.name);
    LockstepParticipant participant(options);
    std::vector<StampedInput<TestSamplePubSubType>*> inputs;
    for (const auto& source : parseNameList("--reads", reads)) {
      inputs.push_back(&participant.input<TestSamplePubSubType>("test/" + source));
    }
    if (!reads_same_step.empty()) {
      for (const auto& source : parseNameList("--reads-same-step", reads_same_step)) {
        inputs.push_back(&participant.input<TestSamplePubSubType>("test/" + source, InputLag::kSameStep));
      }
    }
    auto* output = no_output ? nullptr : &participant.output<TestSamplePubSubType>("test/" + options.name);
    std::ofstream record;
    if (!record_file.empty()) {
      record.open(record_file, std::ios::trunc);
      if (!record) {
        throw ConfigError("--record = '" + record_file + "': cannot write it");
      }
    }
    std::uint64_t state = fnv1a(1469598103934665603ULL, options.name.data(), options.name.size());
    TestSample sample;
    sample.payload().assign(payload, 0.0);
    const int code = participant.run([&](const StepContext& ctx) {
      if (static_cast<std::int64_t>(ctx.step) == fail_at) {
        throw std::runtime_error("failing on purpose at step " + std::to_string(ctx.step));
      }
      if (static_cast<std::int64_t>(ctx.step) == hang_at) {
        spdlog::warn("hanging on purpose at step {}", ctx.step);
        std::this_thread::sleep_for(std::chrono::hours(1));
      }
      state = fnv1a(state, &ctx.step, sizeof(ctx.step));
      for (auto* input : inputs) {
        for (const auto& got : input->get(ctx)) {
          const std::uint64_t value = got.value();
          state = fnv1a(state, &value, sizeof(value));
          if (record.is_open()) {
            record << ctx.step << ' ' << got.source().c_str() << ' ' << got.step() << ' ' << value << '\n';
          }
        }
      }
      if (work_us > 0) {
        spinFor(std::chrono::microseconds(work_us));
      }
      sample.value(state);
      if (!sample.payload().empty()) {
        sample.payload()[0] = static_cast<double>(ctx.step);
      }
      if (output != nullptr) {
        output->write(ctx, sample);
      }
    });
    record.flush();
    return code;
  });
}
