// Loading a campaign config through its declarations, and changing it by dotted path.
#include "bench/campaign_config.hpp"

#include <utility>

#include "bench/config_schema.hpp"
#include "builtin_config.hpp"
#include "config/document.hpp"
#include "config/dotted_path.hpp"
#include "config/errors.hpp"
#include "config/read.hpp"

namespace sb::bench {
namespace {

CampaignConfig read_document(const std::shared_ptr<const config::Document>& document) {
    CampaignConfig c;
    c.source = document->name();
    c.base_dir = document->base_dir();
    c.where.document = document;
    config::Diagnostics diagnostics;
    config::read(campaign_schema(), *document, &c, diagnostics);
    config::check(campaign_schema(), &c, c.where, diagnostics);
    diagnostics.throw_if_any();
    return c;
}

}  // namespace

CampaignConfig load_campaign_config(const std::filesystem::path& path) {
    return read_document(config::Document::parse_file(path));
}

CampaignConfig load_campaign_config_text(std::string_view text, const std::string& name) {
    return read_document(config::Document::parse_text(text, name));
}

std::string_view builtin_config_text() { return kBuiltinConfig; }

config::ConfigError config_problem(const CampaignConfig& config, std::string key, std::string value,
                                   std::string constraint, std::string meaning) {
    return {config.source,     0, 0, std::move(key), std::move(value), std::move(constraint),
            std::move(meaning)};
}

config::Value get_value(const CampaignConfig& config, std::string_view path) {
    return config::get(campaign_schema(), &config, path);
}

void set_value(CampaignConfig& config, std::string_view path, config::Value value,
               const std::string& origin) {
    config::set(campaign_schema(), &config, config.where, path, std::move(value), {origin, 0, 0});
}

void set_value_text(CampaignConfig& config, std::string_view path, std::string_view text,
                    const std::string& origin) {
    config::set_text(campaign_schema(), &config, config.where, path, text, {origin, 0, 0});
}

void apply_overrides(CampaignConfig& config, const std::vector<std::string>& assignments,
                     const std::string& origin) {
    std::vector<config::TextAssignment> batch;
    for (const auto& assignment : assignments) {
        std::string key;
        std::string value;
        if (!config::split_assignment(assignment, key, value)) {
            config::ConfigError e;
            e.file = origin;
            e.key_path = assignment;
            e.constraint = "must be KEY=VALUE";
            e.meaning =
                "a dotted key path and its new value, e.g. "
                "dampers.pd.contact.sliding_friction=0.45";
            throw config::ConfigException({e});
        }
        batch.push_back({key, value});
    }
    config::set_text_all(campaign_schema(), &config, config.where, batch, {origin, 0, 0});
}

}  // namespace sb::bench
