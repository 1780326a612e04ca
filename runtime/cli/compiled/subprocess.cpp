// posix_spawn of /bin/sh -c, the children's output redirected to the log by the spawn itself.

#include "runtime/cli/compiled/subprocess.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <map>
#include <memory>

extern char** environ;

namespace modelgen::internal {

namespace {

// Starts `command` with its output appended to `log`; the child's pid, or -1.
pid_t start_shell(const std::string& command, const std::filesystem::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::string shell = "/bin/sh", dash_c = "-c", text = command;
  char* argv[] = {shell.data(), dash_c.data(), text.data(), nullptr};
  pid_t pid = -1;
  const int failed = posix_spawn(&pid, "/bin/sh", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  return failed != 0 ? -1 : pid;
}

int exit_status(int wait_status) {
  if (WIFEXITED(wait_status)) return WEXITSTATUS(wait_status);
  if (WIFSIGNALED(wait_status)) return 128 + WTERMSIG(wait_status);
  return -1;
}

}  // namespace

std::string shell_quoted(const std::filesystem::path& path) {
  std::string text = "'";
  for (char c : path.string()) text += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return text + "'";
}

std::vector<ChildExit> run_shell_commands(const std::vector<std::string>& commands,
                                          const std::filesystem::path& log, int jobs) {
  std::vector<ChildExit> exits(commands.size());
  std::map<pid_t, std::size_t> running;  // pid -> index of its command
  std::size_t next = 0;
  while (next < commands.size() || !running.empty()) {
    while (next < commands.size() && static_cast<int>(running.size()) < std::max(1, jobs)) {
      const pid_t pid = start_shell(commands[next], log);
      if (pid > 0) running[pid] = next;
      ++next;
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t done = waitpid(-1, &status, 0);
    if (done < 0) break;  // no child left to wait for (never expected)
    const auto it = running.find(done);
    if (it == running.end()) continue;
    exits[it->second].status = exit_status(status);
    running.erase(it);
  }
  return exits;
}

std::string first_output_line(const std::string& command) {
  const std::string quiet = command + " 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(quiet.c_str(), "r"), pclose);
  if (pipe == nullptr) return "";
  std::string line;
  std::array<char, 256> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe.get()) != nullptr) {
    line += buffer.data();
    if (!line.empty() && line.back() == '\n') break;
  }
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line;
}

}  // namespace modelgen::internal
