// Entry points by name: file order from the registry's sections, the needs of each one, and
// the closure of a --functions choice over them.

#include "generator/functions/entry_points.hpp"

#include <algorithm>
#include <set>

#include "generator/functions/registry.hpp"
#include "modelgen/model/command_line.hpp"

namespace modelgen::gen {

std::vector<EntryPoint> entry_points(bool with_estimate) {
  std::vector<EntryPoint> points;
  for (const FunctionEntry& entry : function_registry()) {
    if (entry.emitted == Emitted::kWithEstimate && !with_estimate) continue;
    points.push_back({&entry, false});
  }
  for (const FunctionEntry& entry : function_registry()) {
    if (entry.emitted == Emitted::kWithEstimate && !with_estimate) continue;
    if (entry.variants == Variants::kSincos) points.push_back({&entry, true});
  }
  std::stable_sort(points.begin(), points.end(), [](const EntryPoint& a, const EntryPoint& b) {
    return std::make_pair(a.entry->section, a.sincos) < std::make_pair(b.entry->section, b.sincos);
  });
  return points;
}

std::vector<std::string> entry_point_names(bool with_estimate) {
  std::vector<std::string> names;
  for (const EntryPoint& point : entry_points(with_estimate)) names.push_back(point.name());
  return names;
}

std::vector<std::string> needs(const EntryPoint& point) {
  std::vector<std::string> needed = point.entry->calls;
  if (point.sincos) needed.push_back("joint_sincos");
  return needed;
}

std::string entry_point_list() {
  std::string text;
  for (const EntryPoint& point : entry_points(true)) {
    text += point.name();
    const std::vector<std::string> needed = needs(point);
    for (std::size_t i = 0; i < needed.size(); ++i) text += (i == 0 ? ":" : ",") + needed[i];
    text += "\n";
  }
  return text;
}

namespace {

void check_names(const std::vector<std::string>& selection, bool with_estimate) {
  const std::vector<std::string> valid = entry_point_names(with_estimate);
  for (const std::string& name : selection) {
    if (std::find(valid.begin(), valid.end(), name) != valid.end()) continue;
    if (!with_estimate) {
      const std::vector<std::string> all = entry_point_names(true);
      if (std::find(all.begin(), all.end(), name) != all.end()) {
        throw UsageError("--functions: " + name + " uses identified constants; it needs --params");
      }
    }
    std::string list;
    for (const std::string& v : valid) list += (list.empty() ? "" : ", ") + v;
    throw UsageError("--functions: unknown function '" + name + "'" + did_you_mean(name, valid) +
                     "; the functions are: " + list);
  }
}

// `asked` and, transitively, what each needs; `added` says why each one not asked for came in.
std::set<std::string> close_over_needs(const std::vector<std::string>& asked,
                                       const std::vector<EntryPoint>& all,
                                       std::vector<std::string>& added) {
  std::set<std::string> kept(asked.begin(), asked.end());
  std::vector<std::string> pending(asked.begin(), asked.end());
  while (!pending.empty()) {
    const std::string name = pending.back();
    pending.pop_back();
    for (const EntryPoint& point : all) {
      if (point.name() != name) continue;
      for (const std::string& needed : needs(point)) {
        if (!kept.insert(needed).second) continue;
        pending.push_back(needed);
        added.push_back(needed == "joint_sincos" && point.sincos
                            ? name + " takes sin_q, cos_q from joint_sincos"
                            : name + " calls " + needed);
      }
    }
  }
  return kept;
}

}  // namespace

FunctionSelection select_functions(const std::vector<std::string>& asked, bool with_estimate) {
  FunctionSelection selection;
  selection.every_name = entry_point_names(true);
  const std::vector<EntryPoint> all = entry_points(with_estimate);
  if (asked.empty()) {
    selection.generated = all;
    return selection;
  }
  check_names(asked, with_estimate);
  const std::set<std::string> kept = close_over_needs(asked, all, selection.added);
  for (const EntryPoint& point : all) {
    if (kept.count(point.name()) == 0) continue;
    selection.generated.push_back(point);
    if (std::find(asked.begin(), asked.end(), point.name()) != asked.end()) {
      selection.asked.push_back(point.name());
    }
  }
  return selection;
}

}  // namespace modelgen::gen
