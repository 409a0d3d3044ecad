// A particle damper's describing function: the complex apparent mass M(|a|, f) = -F1/a1 that
// `shakerbench characterize` measured with the enclosure alone under a prescribed harmonic
// motion (docs/characterisation.md), read back from characterization.csv and interpolated
// smoothly in log amplitude and frequency. The "macromodel" of Wong & Rongong and the
// apparent mass of Masmoudi et al. (Granular Matter 18, 2016).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace sb::bench {

struct CampaignConfig;
struct DamperSpec;

/// One characterised grid point of one damper in one arrangement: a row of
/// characterization.csv, the mean (and standard deviation) over the fillings.
struct CharacterizationRow {
    std::string damper;
    std::string arrangement;
    double level_g = 0.0;            ///< RMS of the enclosure's acceleration [g]
    double acceleration_m_s2 = 0.0;  ///< its peak |a1| (a sine: sqrt(2) level) [m/s^2]
    double frequency_hz = 0.0;       ///< [Hz]
    double bed_mass_kg = 0.0;        ///< mass of the particles [kg]
    /// Rotation of the point per unit translation along the excitation direction that went
    /// with the drive (the driven mode's shape at the point; zero: translation only) [rad/m].
    Eigen::Vector3d rotation_per_translation_rad_m = Eigen::Vector3d::Zero();
    int seeds = 0;  ///< fillings averaged
    /// M = -Q1/a1 [kg]: Q the generalised force F.d + M.psi the particles exert on the point,
    /// x(t) = Re{X e^{iwt}}; a rigid mass m gives m; -Im M = 2 P / (w |a1|^2) >= 0.
    std::complex<double> apparent_mass_kg = 0.0;
    double apparent_mass_re_std_kg = 0.0;  ///< standard deviation over the fillings [kg]
    double apparent_mass_im_std_kg = 0.0;  ///< [kg]
    double power_w = 0.0;                  ///< dissipated power: wall work per period / period [W]
    double power_std_w = 0.0;              ///< [W]
    double h2_ratio = 0.0;                 ///< |Q2| / |Q1| [-]
    double h3_ratio = 0.0;                 ///< |Q3| / |Q1| [-]
    double kinetic_j = 0.0;  ///< mean kinetic energy of the particles relative to the enclosure [J]
    double kinetic_std_j = 0.0;  ///< [J]
    double periods = 0.0;        ///< periods simulated per filling, mean [-]
    bool settled = true;         ///< every filling met the steady-state criterion
    int line = 0;                ///< line in the file it was read from (0: made in memory)
};

/// A characterization.csv file: where it came from and its rows.
struct CharacterizationTable {
    std::string config;       ///< the config characterised (file name)
    std::string config_hash;  ///< its hash (bench/resolved_config.hpp)
    /// Per damper: damper_hash() of the config characterised.
    std::vector<std::pair<std::string, std::string>> damper_hashes;
    std::string command;    ///< the command line
    std::string criterion;  ///< the steady-state criterion, as text
    std::vector<CharacterizationRow> rows;
};

/// The text of characterization.csv: `#` lines (format, config, hashes, command, criterion),
/// a header, one row per damper, arrangement, level and frequency (docs/characterisation.md).
std::string characterization_csv_text(const CharacterizationTable& table);

/// Reads characterization.csv; throws identification::FileError (file:line:col) when it cannot
/// be read, a column is missing or unknown, a cell is not what its column needs, or the rows
/// of a damper and arrangement do not form a grid of levels x frequencies.
CharacterizationTable read_characterization_csv(const std::filesystem::path& path);

/// 16 hex digits identifying a damper's physics in a config: every resolved value under
/// dampers.NAME but its model, characterisation file and thread count.
std::string damper_hash(const CampaignConfig& config, const std::string& damper);

/// The characterised apparent mass of one damper in one arrangement, interpolated. Monotone
/// piecewise-cubic Hermite (Fritsch & Carlson, SIAM J. Numer. Anal. 17, 1980) along the
/// frequency, then along log |a1|: continuous with a continuous slope, through every grid
/// value, no overshoot between them. Outside the grid the value is held at its edge.
class DescribingFunction {
  public:
    /// The rows of one damper and arrangement (any order); they must form a grid (every level
    /// at every frequency). `file` names them in messages; throws identification::FileError.
    DescribingFunction(std::vector<CharacterizationRow> rows, const std::string& file);

    struct Value {
        std::complex<double> apparent_mass_kg = 0.0;  ///< M [kg]
        double h2_ratio = 0.0;                        ///< |Q2| / |Q1| [-]
        double h3_ratio = 0.0;                        ///< |Q3| / |Q1| [-]
        bool inside = true;   ///< within the grid's amplitudes and frequencies
        bool settled = true;  ///< every grid point of the cell around it settled
    };
    /// At the peak acceleration |a1| [m/s^2] and frequency [Hz].
    [[nodiscard]] Value evaluate(double acceleration_m_s2, double frequency_hz) const;

    [[nodiscard]] const std::string& damper() const { return damper_; }
    [[nodiscard]] const std::string& arrangement() const { return arrangement_; }
    /// Mean bed mass over the grid [kg].
    [[nodiscard]] double bed_mass_kg() const { return bed_mass_kg_; }
    [[nodiscard]] const Eigen::Vector3d& rotation_per_translation_rad_m() const {
        return rotation_per_translation_;
    }
    [[nodiscard]] const std::vector<double>& accelerations_m_s2() const { return amplitudes_; }
    [[nodiscard]] const std::vector<double>& frequencies_hz() const { return frequencies_; }

  private:
    std::string damper_;
    std::string arrangement_;
    std::vector<double> amplitudes_;   ///< ascending [m/s^2]
    std::vector<double> frequencies_;  ///< ascending [Hz]
    /// Per amplitude i and frequency j (index i * frequencies + j).
    std::vector<CharacterizationRow> grid_;
    double bed_mass_kg_ = 0.0;
    Eigen::Vector3d rotation_per_translation_ = Eigen::Vector3d::Zero();
};

/// The describing function of `damper` in `arrangement` from the table read from `file`,
/// standing for `scale` times the bed characterised (its masses, powers and energies
/// multiplied: dampers.NAME.characterization_scale); throws identification::FileError naming
/// the file when it holds no rows for them.
DescribingFunction describing_function_for(const CharacterizationTable& table,
                                           const std::string& file, const std::string& damper,
                                           const std::string& arrangement, double scale = 1.0);

/// Monotone cubic Hermite interpolation of y(x) at `at` (x ascending, at least one point;
/// held at the ends outside). Exposed for its tests.
double monotone_cubic(const std::vector<double>& x, const std::vector<double>& y, double at);

}  // namespace sb::bench
