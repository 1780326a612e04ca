// The YAML files of an experiment (controller, trajectory), opened the same way: a path that is
// a folder, missing or unreadable, too large or not YAML is an InputError naming it (yaml-cpp's
// own "bad file" and the stream's "basic_filebuf::underflow" texts never reach the user).
// Private to the experiment file formats.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

namespace modelgen::io {

/// The parsed document of `path`; `what` names the file's kind in messages ("a controller
/// file"). Throws InputError with the position of a syntax error.
YAML::Node load_yaml_file(const std::string& path, const std::string& what);

}  // namespace modelgen::io
