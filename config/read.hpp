// Reading a config document into its typed model, and checking the model, with every problem
// reported at the key the user wrote, where it was written.
#pragma once

#include <string>
#include <string_view>

#include "config/errors.hpp"
#include "config/schema.hpp"
#include "config/source_map.hpp"

namespace sb::config {

/// Reads `document` into `object`, the typed model `root` declares: every value is checked
/// against its declaration (type, choices, bound), a missing required key, a key that does
/// not apply and an unknown key are errors. Problems go to `diagnostics`; absent keys leave
/// the member's default.
void read(const Table& root, const Document& document, void* object, Diagnostics& diagnostics);

/// A value of `decl` given as text (a --set on the command line), checked exactly as the same
/// text in the file would be; errors are placed at `origin`. Relative file names resolve in
/// the current folder.
bool value_from_text(const Declaration& decl, std::string_view text, const std::string& path,
                     const Origin& origin, Diagnostics& diagnostics, Value& out);

/// Runs the checks across keys of every table of `object` (innermost first), reporting each
/// violation at the declared key it names, placed by `where`. A check is skipped when an
/// error was already reported within its table.
void check(const Table& root, const void* object, const SourceMap& where, Diagnostics& diagnostics);

}  // namespace sb::config
