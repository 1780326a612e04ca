// Plot output: torques.csv always, plot.gp always, the SVGs through gnuplot when it exists.
// gnuplot runs as a child process in DIR (fork/exec, no shell), its stderr kept for messages.

#include "runtime/cli/plots/torque_plots.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <system_error>

#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace fs = std::filesystem;

namespace {

// gnuplot's single-quoted strings take everything literally but the quote itself.
std::string gnuplot_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Experiments are drawn end to end: experiment e starts where the previous one ended plus one
// of its sample steps, the first keeps its own times. Returns the shift added to each one's t.
std::vector<double> time_shifts(const std::vector<Trajectory>& data) {
  std::vector<double> shifts;
  double next_start = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Eigen::VectorXd& t = data[e].t;
    const double first = t.size() ? t[0] : 0, last = t.size() ? t[t.size() - 1] : 0;
    const double shift = e == 0 ? 0.0 : next_start - first;
    shifts.push_back(shift);
    const double step = t.size() > 1 ? (last - first) / static_cast<double>(t.size() - 1) : 0;
    next_start = last + shift + step;
  }
  return shifts;
}

std::string gnuplot_script(const std::string& title, const std::vector<Trajectory>& data,
                           const TorquePrediction& prediction) {
  const long long n = data.empty() ? 0 : data.front().q.cols();
  const std::size_t experiments = data.size();
  const std::vector<double> shifts = time_shifts(data);
  std::string shift_words;
  for (double shift : shifts) shift_words += (shift_words.empty() ? "" : " ") + shortest(shift);
  std::string s;
  s += "# Measured and predicted joint torques of torques.csv, one SVG per axis; written by\n";
  s += "# modelid. Draw again with: gnuplot plot.gp (in this folder).\n";
  for (std::size_t e = 0; e < experiments; ++e) {
    s += "# experiment " + std::to_string(e + 1) + ": " + data[e].source + "\n";
  }
  s += "set datafile separator ','\n";
  s += "set terminal svg size 1000,700 dynamic noenhanced font 'sans,11'\n";
  s += "set grid\nset key top right\n";
  s += "# Experiments end to end on the time axis: experiment k is shifted by shift(k) s.\n";
  s += "shift(k) = word(\"" + shift_words + "\", k) + 0\n";
  s += "experiments = " + std::to_string(experiments) + "\n";
  for (std::size_t e = 1; e < experiments; ++e) {
    const double boundary = data[e].t[0] + shifts[e];
    s += "set arrow from " + shortest(boundary) + ", graph 0 to " + shortest(boundary) +
         ", graph 1 nohead dashtype 2 linecolor rgb 'gray50'\n";
  }
  // Columns: 1 experiment, 2 t, then tau, tau_pred, error, n each.
  for (long long j = 1; j <= n; ++j) {
    const std::string measured = std::to_string(2 + j), predicted = std::to_string(2 + n + j),
                      error = std::to_string(2 + 2 * n + j);
    const double rms_torque = prediction.rms_torque[j - 1], rms_error = prediction.rms_error[j - 1];
    const std::string relative =
        rms_torque > 0 ? " (" + fixed(100.0 * rms_error / rms_torque, 0, 3) + "% of the rms torque)"
                       : "";
    auto series = [&](const std::string& column, const std::string& color,
                      const std::string& name) {
      return "for [k=1:experiments] 'torques.csv' skip 1 using ($2+shift(k)):($1==k ? $" + column +
             " : NaN) with lines linecolor rgb '" + color + "' title (k==1 ? '" + name + "' : '')";
    };
    s += "\nset output 'axis" + std::to_string(j) + ".svg'\n";
    s += "set multiplot layout 2,1 title " +
         gnuplot_quoted(title + ", axis " + std::to_string(j) + ": rms error " +
                        fixed(rms_error, 0, 3) + relative) +
         "\n";
    s += "set xlabel ''\nset ylabel 'tau" + std::to_string(j) + " (N m or N)'\n";
    s += "plot " + series(measured, "#1f77b4", "measured") + ", \\\n     " +
         series(predicted, "#d62728", "predicted") + "\n";
    s += "set xlabel 'time (s)'\nset ylabel 'measured - predicted'\n";
    s += "plot " + series(error, "#2ca02c", "error") + "\n";
    s += "unset multiplot\nset output\n";
  }
  return s;
}

// Runs `program plot.gp` in `dir`; returns "" on success, else what went wrong (exit status and
// the end of gnuplot's stderr).
std::string run_gnuplot(const std::string& program, const std::string& dir) {
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0) return "cannot create a pipe";
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(pipe_ends[0]);
    ::close(pipe_ends[1]);
    return "cannot start a process";
  }
  if (child == 0) {
    // In the child only async-signal-safe calls until exec.
    const int null = ::open("/dev/null", O_RDWR);
    if (null >= 0) {
      ::dup2(null, STDIN_FILENO);
      ::dup2(null, STDOUT_FILENO);
    }
    ::dup2(pipe_ends[1], STDERR_FILENO);
    ::close(pipe_ends[0]);
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    char* const argv[] = {const_cast<char*>("gnuplot"), const_cast<char*>("plot.gp"), nullptr};
    ::execv(program.c_str(), argv);
    ::_exit(127);
  }
  ::close(pipe_ends[1]);
  std::string messages;
  char buffer[4096];
  for (ssize_t got; (got = ::read(pipe_ends[0], buffer, sizeof buffer)) != 0;) {
    if (got < 0) {
      if (errno == EINTR) continue;
      break;
    }
    messages.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(pipe_ends[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  std::string why = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                      : "killed by a signal";
  while (!messages.empty() && (messages.back() == '\n' || messages.back() == ' ')) {
    messages.pop_back();
  }
  if (messages.size() > 600) messages = "..." + messages.substr(messages.size() - 600);
  return messages.empty() ? why : why + ": " + messages;
}

}  // namespace

void check_plot_folder(const std::string& dir) {
  std::error_code error;
  if (fs::exists(dir, error)) {
    if (!fs::is_directory(dir, error)) {
      throw std::runtime_error(dir + ": error: --plot needs a folder, this is a file");
    }
    if (::access(dir.c_str(), W_OK | X_OK) != 0) {
      throw std::runtime_error(dir + ": error: cannot write into the plot folder: " +
                               std::strerror(errno));
    }
    return;
  }
  // The folder is made only when the plots are written: a run that fails leaves nothing. Here
  // its nearest existing ancestor must be a folder this process can create entries in.
  fs::path ancestor = fs::absolute(fs::path(dir), error).parent_path();
  while (!ancestor.empty() && !fs::exists(ancestor, error) && ancestor != ancestor.root_path()) {
    ancestor = ancestor.parent_path();
  }
  if (!fs::is_directory(ancestor, error)) {
    throw std::runtime_error(dir + ": error: cannot create the plot folder: '" +
                             ancestor.string() + "' is not a folder");
  }
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0) {
    throw std::runtime_error(dir + ": error: cannot create the plot folder: " +
                             std::strerror(errno));
  }
}

std::optional<std::string> find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  const std::string entries = path;
  std::size_t begin = 0;
  while (begin <= entries.size()) {
    std::size_t end = entries.find(':', begin);
    if (end == std::string::npos) end = entries.size();
    // An empty PATH entry means the current folder.
    const std::string folder = end > begin ? entries.substr(begin, end - begin) : ".";
    const std::string candidate = folder + "/" + name;
    std::error_code error;
    if (fs::is_regular_file(candidate, error) && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
    begin = end + 1;
  }
  return std::nullopt;
}

void write_torque_plots(const std::string& dir, const std::string& title,
                        const std::vector<Trajectory>& data, const TorquePrediction& prediction,
                        std::ostream& out, std::ostream& warnings) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    throw std::runtime_error(dir + ": error: cannot create the plot folder: " + error.message());
  }
  const fs::path folder(dir);
  write_file((folder / "torques.csv").string(), prediction_csv(data, prediction, false));
  write_file((folder / "plot.gp").string(), gnuplot_script(title, data, prediction));
  out << "  plots: " << (folder / "torques.csv").string();
  const std::optional<std::string> gnuplot = find_program("gnuplot");
  if (!gnuplot) {
    out << "; axis SVGs skipped: gnuplot is not on PATH (Debian package gnuplot-nox), "
        << (folder / "plot.gp").string() << " draws them\n";
    return;
  }
  const std::string failure = run_gnuplot(*gnuplot, dir);
  if (!failure.empty()) {
    out << "\n";
    warnings << "modelid: warning: gnuplot did not draw the axis SVGs (" << failure << "); "
             << (folder / "torques.csv").string() << " is complete\n";
    return;
  }
  const long long n = data.empty() ? 0 : data.front().q.cols();
  out << ", " << (folder / "axis1.svg").string();
  if (n > 1) out << " .. axis" << n << ".svg";
  out << "\n";
}

}  // namespace modelgen::internal
