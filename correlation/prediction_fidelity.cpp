#include "correlation/prediction_fidelity.hpp"

#include <algorithm>
#include <cmath>

#include "bench/characterization.hpp"
#include "bench/prediction.hpp"
#include "bench/resolved_config.hpp"
#include "core/text_file.hpp"

namespace sb::correlation {

Simulation describing_function_simulation(std::filesystem::path folder, int frequencies) {
    return
        [folder = std::move(folder), frequencies](const bench::CampaignConfig& config,
                                                  const bench::Selection& selection, int threads) {
            bench::CampaignConfig selected = config;
            bench::CharacterizeOptions options;
            options.frequency_count = frequencies;
            options.seeds = std::max(config.campaign.seeds, 1);
            options.threads = threads;
            selected.campaign.arrangement_selection.clear();
            for (const auto& sweep : selection.sweeps) {
                auto& names = selected.campaign.arrangement_selection;
                if (std::find(names.begin(), names.end(), sweep.arrangement) == names.end()) {
                    names.push_back(sweep.arrangement);
                }
                const bool known = std::any_of(
                    options.levels_g.begin(), options.levels_g.end(),
                    [&](double g) { return std::abs(g - sweep.level_g) <= 1e-12 * sweep.level_g; });
                if (!known) options.levels_g.push_back(sweep.level_g);
            }
            std::sort(options.levels_g.begin(), options.levels_g.end());
            const bench::CharacterizeResult characterised = bench::characterize(selected, options);
            const auto file = folder / ("characterization-" + bench::config_hash(config) + ".csv");
            create_directories_for_writing(folder);
            write_file_atomically(file, bench::characterization_csv_text(characterised.table));
            bench::PredictContext context;
            context.selection = selection;
            return bench::predict_campaign(bench::with_describing_functions(config, file), context);
        };
}

}  // namespace sb::correlation
