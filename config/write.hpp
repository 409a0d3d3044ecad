// A typed config written back: the resolved TOML file, its canonical text and its hash.
#pragma once

#include <string>
#include <string_view>

#include "config/schema.hpp"

namespace sb::config {

/// TOML text of `object` with every key that applies written out in declaration order:
/// defaults included, automatic values as "automatic", a `follows` key at the value it takes,
/// file names absolute. Reading it back gives the same model and the same identity_hash().
std::string write_toml(const Table& root, const void* object, std::string_view header_comment);

/// Every resolved value as one line `path = value`, sorted by path: numbers with the digits
/// that read back exactly, a file by the hash of its content (not its place). Independent of
/// key order, comments and formatting in the file the model was read from.
std::string canonical_text(const Table& root, const void* object);

/// 16 hexadecimal digits identifying the canonical text: the same hash, the same numbers.
std::string identity_hash(const Table& root, const void* object);

/// 64-bit FNV-1a of `text` as 16 hexadecimal digits. The hash identifies configs among one
/// user's runs, checkpoints and caches, not against an adversary, so a short,
/// dependency-free hash serves; two different configs collide with probability 2^-64.
std::string fnv1a_hex(std::string_view text);

}  // namespace sb::config
