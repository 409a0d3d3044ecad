// Reading a campaign config file section by section.
#include "bench/campaign_config.hpp"

#include "bench/config_reader.hpp"
#include "bench/structure_config.hpp"
#include "builtin_config.hpp"

namespace sb::bench {
namespace {

CampaignConfig read_document(ConfigDocument document) {
    CampaignConfig config;
    config.source = document.diagnostics().file();
    config.base_dir = document.base_dir();
    Section root = Section::root(document);

    Section campaign = root.table("campaign", "campaign identity");
    config.name = campaign.string("name", "campaign", "campaign name, used in output names");
    config.description = campaign.string("description", "", "free text");
    campaign.finish();

    config.structure =
        read_structure(root.table("structure", "the structure under test"), config.base_dir);
    root.finish();
    document.diagnostics().throw_if_any();
    return config;
}

}  // namespace

CampaignConfig load_campaign_config(const std::filesystem::path& path) {
    return read_document(ConfigDocument::parse_file(path));
}

CampaignConfig load_campaign_config_text(std::string_view text, const std::string& name) {
    return read_document(ConfigDocument::parse_text(text, name));
}

std::string_view builtin_config_text() { return kBuiltinConfig; }

}  // namespace sb::bench
