// Campaign configs for tests: the shipped H-0 campaign with lines replaced.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "config/errors.hpp"
#include "config/value.hpp"
#include "core/text_file.hpp"
#include "structure/spec.hpp"

namespace sb::bench::test {

/// The shipped H-0 campaign with its lines starting with `key` replaced.
inline std::string paper000_h0_with(const std::vector<std::pair<std::string, std::string>>& edits) {
    std::string text = read_text_file(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    for (const auto& [key, line] : edits) {
        const auto at = text.find("\n" + key);
        EXPECT_NE(at, std::string::npos) << key;
        const auto end = text.find('\n', at + 1);
        text.replace(at + 1, end - at - 1, line);
    }
    return text;
}

/// The H-0 damper with 30 spheres at the levels of `levels_line` (`levels_g = [...]`).
inline CampaignConfig thirty_sphere_h0(const std::string& levels_line, const std::string& name) {
    const std::string text = paper000_h0_with({
        {"count = 120", "count = 30"},
        {"max_overlap_fraction", "max_overlap_fraction = 0.05"},
        {"levels_g", levels_line},
    });
    return load_campaign_config_text(text, name);
}

/// The paper-000 bench with its particles as a rigid mass (a linear structure) at 1 and 3 g,
/// `count` frequencies over ±4 % of the mode. A catalogue physics switched on starts each
/// point from the linear steady state without it, a transient that the lightly damped mode
/// sheds by e^-1 in about 25 periods: the controller skips 60 after each change and holds the
/// level within 0.2 %, or the 5 % default would take the transient's amplitude for the
/// steady one.
inline CampaignConfig linear_paper000_bench(int count) {
    auto config = load_campaign_config_text(paper000_h0_with({}), "linear-bench.toml");
    config.campaign.dampers.front().model = DamperSpec::Model::rigid;
    config.campaign.levels_g = {1.0, 3.0};
    config.campaign.frequencies.count = count;
    config.campaign.frequencies.low_ratio = 0.96;
    config.campaign.frequencies.high_ratio = 1.04;
    config.campaign.controller.tolerance = 0.002;
    config.campaign.controller.transient_periods = 60;
    config.campaign.controller.max_periods = 400;
    return config;
}

/// `text` with the frequency grid kept as given: no frequencies added where the estimates
/// are unresolved (for tests of something other than the grid).
inline std::string without_refinement(std::string text) {
    const std::string table = "[campaign.frequencies]\n";
    const auto at = text.find(table);
    EXPECT_NE(at, std::string::npos);
    text.insert(at + table.size(), "refine_points = 0\n");
    return text;
}

/// An empty directory for one test of this process: the process id keeps concurrent runs
/// (other build trees, other users) from resuming each other's checkpoints.
inline std::filesystem::path fresh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("shakerbench-campaign-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

/// Adds `bed` (enclosure frame, the enclosure at `origin` turned by `rotation` from the
/// point) to `spec` as one rigid lumped mass at `point`: mass, centre of gravity and the
/// inertia of spheres about it (the diagonal about x, y, z).
inline void add_rigid_bed(structure::StructureSpec& spec, const std::string& point,
                          const std::string& name, const Eigen::Vector3d& origin,
                          const Eigen::Matrix3d& rotation,
                          const std::vector<Eigen::Vector3d>& local,
                          const std::vector<double>& radii_m, double density_kg_m3) {
    double mass = 0.0;
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
    std::vector<double> masses;
    for (std::size_t i = 0; i < local.size(); ++i) {
        const double r = radii_m[i];
        masses.push_back(density_kg_m3 * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r);
        mass += masses.back();
        first_moment += masses.back() * (origin + rotation * local[i]);
    }
    const Eigen::Vector3d cg = first_moment / mass;
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < local.size(); ++i) {
        const Eigen::Vector3d d = origin + rotation * local[i] - cg;
        inertia += masses[i] * ((d.squaredNorm() + 0.4 * radii_m[i] * radii_m[i]) *
                                    Eigen::Matrix3d::Identity() -
                                d * d.transpose());
    }
    double x_m = 0.0;
    for (const auto& p : spec.beam.points) {
        if (p.name == point) x_m = p.x_m;
    }
    structure::LumpedMass bed;
    bed.name = name;
    bed.x_m = x_m;
    bed.mass_kg = mass;
    bed.offset_m = cg;
    bed.inertia_kg_m2 = inertia.diagonal();
    spec.beam.masses.push_back(bed);
}

/// Every regular file under `dir`, relative path -> content.
inline std::vector<std::pair<std::string, std::string>> files_under(
    const std::filesystem::path& dir) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        if (entry.is_regular_file()) {
            out.emplace_back(std::filesystem::relative(entry.path(), dir).string(),
                             read_text_file(entry.path()));
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// The [arrangements] and [structure] of a config for a 0.05 kg table on a 2e4 N/m spring
/// (100.7 Hz), `damping_ratio` modal damping, moving vertically, driven by a force at the
/// table or, `base_driven`, through the ground; the [campaign] and any damper are the
/// caller's.
inline std::string table_on_a_spring(double damping_ratio, bool base_driven = false) {
    return R"(
[arrangements.V]
oscillation = "vertical"
[structure]
kind = "lumped"
[[structure.lumped.masses]]
name = "table"
mass_kg = 0.05
[[structure.lumped.springs]]
from = "ground"
to = "table"
stiffness_n_per_m = 2e4
[structure.damping]
default_ratio = )" +
           config::number_text(damping_ratio) + R"(
[structure.excitation]
)" + std::string(base_driven ? "kind = \"base\"\nsupport = \"ground\"\n" : "point = \"table\"\n");
}

/// The text of the ConfigException loading `text` (as `file_name`) throws, or a failure.
inline std::string config_error(const std::string& text, const std::string& file_name) {
    try {
        (void)load_campaign_config_text(text, file_name);
    } catch (const config::ConfigException& e) {
        return e.what();
    }
    ADD_FAILURE() << "no ConfigException";
    return {};
}

/// The campaign of `config` in memory on one thread, with `store` (none: nothing kept).
inline CampaignResult run_on_one_thread(const CampaignConfig& config,
                                        CheckpointStore* store = nullptr) {
    CampaignContext context;
    context.threads = 1;
    context.store = store;
    return run_campaign(config, context);
}

}  // namespace sb::bench::test
