// The identified MDH YAML: a text edit of the top-level `known:` block found through yaml-cpp's
// marks, so comments and layout elsewhere stay as the user wrote them.

#include "modelgen/model/yaml_export.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"

namespace modelgen {

namespace {

const std::string kNoteStart = "Identified by modelid export";

// The lines of `text`, each with its line break.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
    lines.push_back(text.substr(start, stop - start));
    start = stop;
  }
  return lines;
}

bool blank_or_top_comment(const std::string& line) {
  return line.find_first_not_of(" \t\r\n") == std::string::npos || line.front() == '#';
}

std::string known_section(const RobotModel& description, const Eigen::VectorXd& standard,
                          const std::string& note) {
  std::string out;
  for (const std::string& line : lines_of(note + "\n")) out += "# " + line;
  out += "known:\n";
  for (std::size_t b = 0; b < description.tree.bodies.size(); ++b) {
    std::string entries;
    for (std::size_t k = 0; k < description.tree.params.size(); ++k) {
      const StandardParam& param = description.tree.params[k];
      if (param.body != static_cast<int>(b)) continue;
      entries += "  " + param.name + ": " +
                 shortest_text(standard[static_cast<Eigen::Index>(k)] + 0.0) + "\n";
    }
    if (!entries.empty())
      out +=
          "  # link " + std::to_string(b + 1) + " (" + description.joints[b].name + ")\n" + entries;
  }
  return out;
}

}  // namespace

std::string identified_yaml(const std::string& path, const std::string& text,
                            const RobotModel& description, const Eigen::VectorXd& standard,
                            const std::string& note) {
  const YAML::Node root = YAML::Load(text);  // loaded once already: no syntax error here
  int known_line = -1;
  std::vector<int> key_lines;
  for (const auto& entry : root) {
    key_lines.push_back(entry.first.Mark().line);
    if (entry.first.Scalar() == "known") known_line = entry.first.Mark().line;
  }
  std::vector<std::string> lines = lines_of(text);
  const std::string section = known_section(description, standard, note);
  if (known_line < 0) {
    std::string out = text;
    if (!out.empty() && out.back() != '\n') out += '\n';
    return out + section;
  }
  if (std::count(key_lines.begin(), key_lines.end(), known_line) > 1) {
    throw InputError({path, known_line + 1, 0},
                     "'known' shares its line with another top-level key; put each top-level "
                     "key on a line of its own for export to replace 'known'");
  }
  int next_line = static_cast<int>(lines.size());
  for (int line : key_lines) {
    if (line > known_line) next_line = std::min(next_line, line);
  }
  // The comments just above the next key are that key's.
  while (next_line > known_line + 1 &&
         blank_or_top_comment(lines[static_cast<std::size_t>(next_line - 1)])) {
    --next_line;
  }
  // A section an earlier export wrote goes with the comment it wrote above it.
  int start = known_line;
  while (start > 0 && lines[static_cast<std::size_t>(start - 1)].rfind("# ", 0) == 0) --start;
  if (lines[static_cast<std::size_t>(start)].rfind("# " + kNoteStart, 0) != 0) start = known_line;
  std::string out;
  for (int i = 0; i < start; ++i) out += lines[static_cast<std::size_t>(i)];
  out += section;
  for (std::size_t i = static_cast<std::size_t>(next_line); i < lines.size(); ++i) out += lines[i];
  return out;
}

}  // namespace modelgen
