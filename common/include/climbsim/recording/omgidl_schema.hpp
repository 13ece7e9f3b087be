#pragma once
/// @file
/// The self-contained OMG IDL text of a message type, as an MCAP schema of encoding `omgidl`
/// holds it (docs/recordings.md#what-runmcap-holds): a reader that knows nothing of climbsim
/// decodes the CDR samples of a channel from it alone.

#include <string>
#include <utility>
#include <vector>

namespace climbsim::recording {

/// An IDL file: {file name, text}.
using IdlText = std::pair<std::string, std::string>;

/// The IDL files this build was generated from: idl/*.idl (embedded by idl/CMakeLists.txt) and
/// the vendored Foxglove schemas (module foxglove, common/third_party/foxglove_schemas).
std::vector<IdlText> builtIdlTexts();

/// The definition of `type_name` ("module::Name", e.g. "climbsim::ChamberState") and of every
/// definition it uses, directly or not (structs, enums, unions, typedefs, constants of the
/// same module), each used one before its user, each inside its `module NAME { ... };`,
/// without comments and preprocessor lines. Supports one level of modules, as idl/ has.
/// std::invalid_argument if no file defines the type, or a text does not parse (naming the
/// file).
std::string omgidlSchemaText(const std::vector<IdlText>& files, const std::string& type_name);

/// omgidlSchemaText over builtIdlTexts(), which are parsed once per process.
std::string omgidlSchemaText(const std::string& type_name);

}  // namespace climbsim::recording
