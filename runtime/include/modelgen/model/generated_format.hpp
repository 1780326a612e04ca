// The version of the generated code's interface (function names, argument layouts, the model
// struct): the generator writes it into every generated header as kFormatVersion, and the
// runtime's adapter (identification_model.hpp) refuses generated code of another version at
// compile time. Change it with the templates, regenerate generated/, and say why.
#pragma once

namespace modelgen {

constexpr int kGeneratedFormatVersion = 5;

}  // namespace modelgen
