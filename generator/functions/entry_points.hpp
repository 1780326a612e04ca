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
/// prints and modelgen_generate() mirrors (MODELGEN_ENTRY_POINTS).
std::string entry_point_list();

/// The entry points to generate for `selection` (--functions; empty: all), in file order: the
/// selection and, transitively, what it needs. `added` (if given) receives "x calls y" or "x
/// takes sin_q, cos_q from joint_sincos" for each one needed that was not asked for. Throws
/// UsageError for a name that is not an entry point of a model `with_estimate` or not.
std::vector<EntryPoint> select_entry_points(const std::vector<std::string>& selection,
                                            bool with_estimate,
                                            std::vector<std::string>* added = nullptr);

}  // namespace modelgen::gen
