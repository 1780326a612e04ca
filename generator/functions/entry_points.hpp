// The entry points of a generated model as names: their order in the files, what each needs
// besides itself, and the choice of --functions (validated, closed over those needs).
#pragma once

#include <string>
#include <vector>

#include "generator/functions/function_entry.hpp"

namespace modelgen::gen {

/// One entry point: a registry entry, plain or its _sincos variant.
struct EntryPoint {
  const FunctionEntry* entry;
  bool sincos;
  std::string name() const { return std::string(entry->name) + (sincos ? "_sincos" : ""); }
};

/// Every entry point in file order: the sections in their order, each with its functions in
/// registry order followed by their _sincos variants; the functions on identified constants
/// only `with_estimate`.
std::vector<EntryPoint> entry_points(bool with_estimate);

/// The names of entry_points(with_estimate): what --functions accepts.
std::vector<std::string> entry_point_names(bool with_estimate);

/// The entry points `point` needs beside it: those its body calls, and for a _sincos variant
/// joint_sincos, which computes its sin_q and cos_q.
std::vector<std::string> needs(const EntryPoint& point);

/// Every entry point (entry_point_names(true)), one per line, followed by ":" and the entry
/// points it needs, comma-separated, when it needs any: what `modelgen --list-functions`
/// prints, from which modelgen_generate() learns the files of each --functions choice.
std::string entry_point_list();

/// The functions of one modelgen run, chosen once (select_functions) and handed to the emitter.
struct FunctionSelection {
  /// The entry points to generate, in file order: those asked for and, transitively, what
  /// they need; every one when none was asked for.
  std::vector<EntryPoint> generated;
  /// The names asked for (--functions), once each and in file order (the banner's command
  /// line); empty for all.
  std::vector<std::string> asked;
  /// For each one generated that was not asked for: "x calls y" or "x takes sin_q, cos_q from
  /// joint_sincos".
  std::vector<std::string> added;
  /// Every entry point of any model (entry_point_names(true)): the files an earlier run into
  /// the same folder may have left.
  std::vector<std::string> every_name;
};

/// The functions to generate for `asked` (--functions; empty: all) in a model `with_estimate`
/// or not. Throws UsageError for a name that is not an entry point of such a model.
FunctionSelection select_functions(const std::vector<std::string>& asked, bool with_estimate);

}  // namespace modelgen::gen
