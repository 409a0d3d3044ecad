// The key reference: every declared key listed for `shakerbench keys`, and the tables of
// docs/config.md generated from the declarations.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "config/schema.hpp"

namespace sb::config {

/// One value key.
struct KeyRow {
    std::string path;  ///< "dampers.pd.contact.restitution", or "dampers.NAME.contact..."
    const Declaration* decl = nullptr;
    std::string value;  ///< its value in the object, or its default
};

/// Every value key in declaration order: with `object`, the keys of that config (names and
/// indexes filled in, keys that do not apply left out) and their values; with nullptr, the
/// generic keys (NAME, [i]) and their defaults.
std::vector<KeyRow> key_rows(const Table& root, const void* object);

/// A table as docs/config.md documents it.
struct DocumentedTable {
    std::string header;            ///< "[dampers.NAME.contact]", "[[structure.beam.masses]]"
    const Table* table = nullptr;  ///< its declarations (null for NAME = number tables)
    const Declaration* element = nullptr;  ///< NAME = number tables: each number
};

/// Every table that holds value keys, in declaration order.
std::vector<DocumentedTable> documented_tables(const Table& root);

/// The markdown rows (header included) of one documented table.
std::string markdown_table(const DocumentedTable& table);

/// `text` with every block `<!-- keys HEADER -->` ... `<!-- /keys -->` holding the current
/// markdown table of that header. A block naming no table, and a documented table without a
/// block, are added to `problems`.
std::string update_key_blocks(std::string_view text, const Table& root,
                              std::vector<std::string>& problems);

}  // namespace sb::config
