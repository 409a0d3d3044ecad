// Every value of a loaded config addressed by its dotted path: read it, or change it as if
// the file had held the new value.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "config/errors.hpp"
#include "config/schema.hpp"
#include "config/source_map.hpp"

namespace sb::config {

/// The value at `path` ("dampers.pd.contact.sliding_friction",
/// "structure.beam.masses[1].mass_kg", "structure.beam.points.damper", one number of a vector
/// or an array: "structure.excitation.direction[2]") as the bench uses it:
/// a `follows` key resolved, std::monostate for an automatic or absent value. Throws
/// ConfigException when the path names no value.
Value get(const Table& root, const void* object, std::string_view path);

/// The declaration of the value at `path` (throws like get()).
const Declaration& declaration(const Table& root, const void* object, std::string_view path);

/// Changes the value at `path` as if the file had held `value`: checked against its
/// declaration, then every check across keys runs on the whole model. On any problem the
/// model is left as it was and ConfigException is thrown, this key's errors placed at
/// `origin` and the others by `where`. On success `where` records the override.
void set(const Table& root, void* object, SourceMap& where, std::string_view path, Value value,
         const Origin& origin);

/// The same with the value as text: TOML (0.45, 3, true, "name", [0, 0, 1]) or a bare word
/// (linear-steady-state, automatic).
void set_text(const Table& root, void* object, SourceMap& where, std::string_view path,
              std::string_view text, const Origin& origin);

/// One change of a batch: a dotted path and its value as text (as set_text() takes it).
struct TextAssignment {
    std::string path;
    std::string text;
};

/// Changes several values together, as if the file had held all of them: each is checked
/// against its declaration, then the checks across keys run once on the whole model, so values
/// that are only valid together (a damper model and the file it reads; a frequency band moved
/// past its other end) can be set in any order. Every error of every key is reported at once;
/// on any problem the model is left as it was.
void set_text_all(const Table& root, void* object, SourceMap& where,
                  const std::vector<TextAssignment>& assignments, const Origin& origin);

/// Splits "KEY=VALUE" at its first '='; false when there is none or the key is empty.
bool split_assignment(std::string_view assignment, std::string& key, std::string& value);

}  // namespace sb::config
