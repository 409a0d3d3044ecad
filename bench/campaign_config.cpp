// Reading a campaign config file section by section.
#include "bench/campaign_config.hpp"

#include <algorithm>

#include "bench/campaign_reader.hpp"
#include "bench/config_reader.hpp"
#include "bench/structure_config.hpp"
#include "builtin_config.hpp"

namespace sb::bench {
namespace {

/// Names a structure of this spec offers as points (beam: points and named masses; lumped:
/// masses; matrix: the prefixes of named DOFs).
std::vector<std::string> point_names(const structure::StructureSpec& spec) {
    std::vector<std::string> names;
    switch (spec.kind) {
        case structure::StructureSpec::Kind::beam:
            for (const auto& p : spec.beam.points) names.push_back(p.name);
            for (const auto& m : spec.beam.masses) names.push_back(m.name);
            for (const auto& s : spec.beam.supports) names.push_back(s.name);
            break;
        case structure::StructureSpec::Kind::lumped:
            for (const auto& m : spec.lumped.masses) names.push_back(m.name);
            break;
        case structure::StructureSpec::Kind::matrix:
            for (const auto& [dof, row] : spec.matrix.named_dofs) {
                names.push_back(dof.substr(0, dof.rfind('.')));
            }
            break;
    }
    return names;
}

/// True when a beam structure has a lumped mass named `mass` at the position of `point`.
bool has_lumped_mass(const structure::StructureSpec& spec, const std::string& mass,
                     const std::string& point) {
    if (spec.kind != structure::StructureSpec::Kind::beam) return false;
    for (const auto& p : spec.beam.points) {
        if (p.name != point) continue;
        for (const auto& m : spec.beam.masses) {
            if (m.name == mass && m.x_m == p.x_m) return true;
        }
    }
    return false;
}

/// Every point the campaign refers to must exist in the structure.
void check_points(const CampaignConfig& config, Section& campaign, Section& root) {
    const auto names = point_names(config.structure);
    const auto known = [&](const std::string& name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    const bool runs = !config.campaign.levels_g.empty();
    if (runs && !known(config.campaign.control_point)) {
        campaign.error("control_point", "\"" + config.campaign.control_point + "\"",
                       "must name a point of the structure", "the controlled point");
    }
    for (const auto& p : config.campaign.response_points) {
        if (!known(p)) {
            campaign.error("response_points", "\"" + p + "\"", "must name a point of the structure",
                           "recorded points");
        }
    }
    Section dampers = root.table("dampers", "particle dampers");
    for (const auto& d : config.campaign.dampers) {
        if (!known(d.point)) {
            Section damper = dampers.table(d.name, "a damper");
            damper.error("point", "\"" + d.point + "\"", "must name a point of the structure",
                         "where the damper is attached");
        }
        if (!d.enclosure_mass.empty() &&
            !has_lumped_mass(config.structure, d.enclosure_mass, d.point)) {
            Section damper = dampers.table(d.name, "a damper");
            damper.error("enclosure_mass", "\"" + d.enclosure_mass + "\"",
                         "must name a [[structure.beam.masses]] entry at point \"" + d.point + "\"",
                         "the structure mass that is this damper's enclosure");
        }
    }
}

CampaignConfig read_document(ConfigDocument document) {
    CampaignConfig config;
    config.source = document.diagnostics().file();
    config.base_dir = document.base_dir();
    Section root = Section::root(document);

    Section campaign = root.table("campaign", "campaign identity");
    config.name = campaign.string("name", "campaign", "campaign name, used in output names");
    config.description = campaign.string("description", "", "free text");
    config.structure =
        read_structure(root.table("structure", "the structure under test"), config.base_dir);
    config.campaign = read_campaign(root, campaign);
    check_points(config, campaign, root);
    campaign.finish();
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
