// deploy/climbsim's usage text (`deploy/climbsim --help`) against the commands behind it: every
// option listed under a command is one that command takes, and every option a command takes
// is listed under it. The launcher's commands are read from its CLI11 app (cli.hpp), solo's
// and sweep's from their own --help.

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli.hpp"

namespace {

/// Standard output of `command` (run by /bin/sh); fails the test on a non-zero exit.
std::string outputOf(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return out;
  }
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command << " failed:\n" << out;
  return out;
}

/// The usage text by command: a line "  NAME ..." (two spaces, then the command) starts a
/// command's block; the lines indented further below it belong to it.
std::map<std::string, std::string> usageBlocks(const std::string& usage) {
  std::map<std::string, std::string> blocks;
  const std::regex command_line(R"(^  ([a-z]+)( .*)?$)");
  std::istringstream lines(usage);
  std::string line;
  std::string current;
  std::smatch m;
  while (std::getline(lines, line)) {
    if (std::regex_match(line, m, command_line)) {
      current = m[1];
      blocks[current] += line + "\n";
    } else if (!current.empty() && line.rfind("   ", 0) == 0) {
      blocks[current] += line + "\n";
    } else {
      current.clear();
    }
  }
  return blocks;
}

/// Every option named in `text`: "-d", "--set", ... (not the '-' inside a word like two-hosts).
std::set<std::string> optionsNamedIn(const std::string& text) {
  std::set<std::string> names;
  const std::regex option(R"((^|[^\w-])(--?[A-Za-z][\w-]*))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it) {
    names.insert((*it)[2]);
  }
  return names;
}

/// The options a CLI11 command takes, as written on a command line ("-f", "--file", ...).
std::set<std::string> optionsOf(const CLI::App& command, bool with_help) {
  std::set<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    if (!with_help && option == command.get_help_ptr()) continue;
    for (const auto& name : option->get_snames()) names.insert("-" + name);
    for (const auto& name : option->get_lnames()) names.insert("--" + name);
  }
  return names;
}

/// The options a program's CLI11 --help lists: the names at the start of its option lines.
std::set<std::string> optionsInHelp(const std::string& help, bool with_help) {
  std::set<std::string> names;
  const std::regex option_line(R"(^  (-[^ ]+))");
  std::istringstream lines(help);
  std::string line;
  std::smatch m;
  while (std::getline(lines, line)) {
    if (!std::regex_search(line, m, option_line)) continue;
    std::istringstream list(m[1].str());
    std::string name;
    while (std::getline(list, name, ',')) {
      if (with_help || (name != "-h" && name != "--help")) names.insert(name);
    }
  }
  return names;
}

std::string joined(const std::set<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : " ") + name;
  return out;
}

class Help : public ::testing::Test {
 protected:
  void SetUp() override { blocks_ = usageBlocks(outputOf("bash '" CLIMBSIM_ROOT "/deploy/climbsim' --help")); }

  /// Expects the usage block of `command` to name exactly the options in `taken` (`accepted`
  /// may add the help option, which the usage need not list).
  void expectListed(const std::string& command, const std::set<std::string>& taken,
                    const std::set<std::string>& accepted) {
    ASSERT_EQ(blocks_.count(command), 1u) << "deploy/climbsim --help has no line for '" << command << "'";
    const std::set<std::string> listed = optionsNamedIn(blocks_.at(command));
    std::set<std::string> not_taken;
    for (const auto& name : listed) {
      if (accepted.count(name) == 0) not_taken.insert(name);
    }
    EXPECT_TRUE(not_taken.empty()) << "listed under '" << command << "' but '" << command
                                   << "' does not take: " << joined(not_taken) << "\n"
                                   << blocks_.at(command);
    std::set<std::string> unlisted;
    for (const auto& name : taken) {
      // An option with a short and a long name is listed by either.
      if (listed.count(name) == 0) unlisted.insert(name);
    }
    std::set<std::string> missing;
    for (const auto& name : unlisted) {
      const bool other_name_listed = std::any_of(listed.begin(), listed.end(), [&](const std::string& l) {
        return aliases_.count(l) && aliases_.at(l) == aliases_.at(name);
      });
      if (!other_name_listed) missing.insert(name);
    }
    EXPECT_TRUE(missing.empty()) << "'" << command << "' takes but deploy/climbsim --help does not list under it: "
                                 << joined(missing) << "\n"
                                 << blocks_.at(command);
  }

  std::map<std::string, std::string> blocks_;
  /// Option name -> one key per option, so that "-f" and "--file" count as one.
  std::map<std::string, std::string> aliases_;
};

TEST_F(Help, EveryLauncherCommandListsExactlyTheOptionsItTakes) {
  climbsim::launcher::CliValues values;
  const auto app = climbsim::launcher::makeComposeCli(values);
  const auto commands = app->get_subcommands([](const CLI::App*) { return true; });
  ASSERT_GE(commands.size(), 7u) << "up, run, view, down, ps, logs, topics";
  for (const CLI::App* command : commands) {
    for (const CLI::Option* option : command->get_options()) {
      const std::string key = command->get_name() + ":" + option->get_name();
      for (const auto& name : option->get_snames()) aliases_["-" + name] = key;
      for (const auto& name : option->get_lnames()) aliases_["--" + name] = key;
    }
    expectListed(command->get_name(), optionsOf(*command, false), optionsOf(*command, true));
    aliases_.clear();
  }
}

TEST_F(Help, SoloAndSweepListExactlyTheOptionsTheirProgramsTake) {
  const std::map<std::string, std::string> programs = {{"solo", CLIMBSIM_SOLO_EXE}, {"sweep", CLIMBSIM_SWEEP_EXE}};
  for (const auto& [command, program] : programs) {
    const std::string help = outputOf("'" + program + "' --help");
    const std::regex option_line(R"(^  (-[^ ]+))");
    std::istringstream lines(help);
    std::string line;
    std::smatch m;
    while (std::getline(lines, line)) {
      if (!std::regex_search(line, m, option_line)) continue;
      std::istringstream list(m[1].str());
      std::string name;
      while (std::getline(list, name, ',')) aliases_[name] = m[1].str();
    }
    expectListed(command, optionsInHelp(help, false), optionsInHelp(help, true));
    aliases_.clear();
  }
}

TEST_F(Help, TheOtherCommandsListNoOptions) {
  for (const char* command : {"setup", "build", "test", "bench", "hosts"}) {
    ASSERT_EQ(blocks_.count(command), 1u) << command;
    EXPECT_TRUE(optionsNamedIn(blocks_.at(command)).empty()) << blocks_.at(command);
  }
}

TEST(HelpText, ATopicsLineThatNamesTheViewerOptionIsCaughtAsNotTakenByTopics) {
  // The check itself: --viewer under `topics` is an option `topics` does not take.
  const auto blocks = usageBlocks(
      "usage: x\n  topics           the table of every DDS topic\n                   --viewer: also start the viewer\n"
      "  view RUN_DIR [--port P]\n");
  ASSERT_EQ(blocks.count("topics"), 1u);
  EXPECT_EQ(optionsNamedIn(blocks.at("topics")), std::set<std::string>{"--viewer"});
  EXPECT_EQ(optionsNamedIn(blocks.at("view")), std::set<std::string>{"--port"});
  climbsim::launcher::CliValues values;
  const auto app = climbsim::launcher::makeComposeCli(values);
  EXPECT_EQ(optionsOf(*app->get_subcommand("topics"), false).count("--viewer"), 0u);
  EXPECT_EQ(optionsOf(*app->get_subcommand("run"), false).count("--viewer"), 1u);
  EXPECT_EQ(optionsOf(*app->get_subcommand("up"), false).count("--viewer"), 0u);
}

}  // namespace
