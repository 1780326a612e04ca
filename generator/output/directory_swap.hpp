// Replacing a whole output folder at once: the new set is built in a sibling folder (files
// whose content did not change hard-linked from the old one, so they keep their inode and
// modification time), then exchanged with the output folder by one renameat2(RENAME_EXCHANGE)
// (Linux 3.15), or renamed into place when there was no folder yet. Whoever looks at the
// output folder sees the complete old set or the complete new set, never a mix, even if the
// run is killed at any point; a killed run only leaves a hidden sibling folder that the next
// run removes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generator/output/file_set.hpp"

namespace modelgen::gen::detail {

/// What one swap does. `directory` is absolute, its symbolic links resolved (the folder a link
/// points to is replaced, not the link), and names a folder or nothing.
struct SwapPlan {
  std::filesystem::path directory;
  std::vector<const OutputFile*> written;  ///< written anew
  std::vector<std::string> linked;         ///< kept as they are, hard-linked from the old folder
  /// Every name the old folder held when the plan was made: they go with the old set. A name
  /// that appears in the old folder during the swap (another program writing there) is moved
  /// back beside the new set unless the new set has that name.
  std::vector<std::string> old_names;
};

enum class SwapResult {
  kDone,         ///< the new set is in place, the old one removed
  kUnsupported,  ///< nothing changed: the file system cannot do it here (no RENAME_EXCHANGE,
                 ///< another file system or a mount point, the parent folder not writable, a
                 ///< folder whose owner or access lists a new folder could not copy)
};

/// Carries out `plan`. Throws InputError naming the file and the system's reason when a file
/// of the new set cannot be written; the output folder is then unchanged and the sibling folder
/// removed.
SwapResult swap_in_directory(const SwapPlan& plan);

}  // namespace modelgen::gen::detail
