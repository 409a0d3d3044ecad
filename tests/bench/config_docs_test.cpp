// docs/config.md documents exactly the declared keys: its key tables are generated from the
// declarations (shakerbench-config-docs --write docs/config.md) and checked here.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "bench/config_schema.hpp"
#include "config/reference.hpp"
#include "core/text_file.hpp"

namespace sb::bench {
namespace {

std::string config_doc() { return read_text_file(std::string(SB_SOURCE_DIR) + "/docs/config.md"); }

TEST(ConfigDocs, TheKeyTablesOfTheConfigReferenceAreTheDeclarations) {
    const std::string text = config_doc();
    std::vector<std::string> problems;
    const std::string generated = config::update_key_blocks(text, campaign_schema(), problems);
    for (const auto& p : problems) ADD_FAILURE() << "docs/config.md: " << p;
    EXPECT_TRUE(generated == text)
        << "docs/config.md is stale: run shakerbench-config-docs --write docs/config.md";
}

/// The generic dotted path of every key row of docs/config.md's key tables.
std::set<std::string> documented_keys(const std::string& text) {
    std::set<std::string> keys;
    std::istringstream in(text);
    std::string header;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("<!-- keys ", 0) == 0) {
            header = line.substr(10, line.size() - 10 - 4);
            if (header.rfind("[[", 0) == 0) {
                header = header.substr(2, header.size() - 4) + "[i]";
            } else {
                header = header.substr(1, header.size() - 2);
            }
        } else if (line.rfind("<!-- /keys -->", 0) == 0) {
            header.clear();
        } else if (!header.empty() && line.rfind("| `", 0) == 0) {
            const auto end = line.find('`', 3);
            keys.insert(header + "." + line.substr(3, end - 3));
        }
    }
    return keys;
}

TEST(ConfigDocs, EveryDocumentedKeyIsDeclaredAndEveryDeclaredKeyIsDocumented) {
    const auto documented = documented_keys(config_doc());
    std::set<std::string> declared;
    for (const auto& row : config::key_rows(campaign_schema(), nullptr)) declared.insert(row.path);
    for (const auto& key : documented) {
        EXPECT_TRUE(declared.contains(key)) << key << " is documented but not declared";
    }
    for (const auto& key : declared) {
        EXPECT_TRUE(documented.contains(key)) << key << " is declared but not documented";
    }
    EXPECT_GT(declared.size(), 100u);
}

}  // namespace
}  // namespace sb::bench
