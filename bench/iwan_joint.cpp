#include "bench/iwan_joint.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sb::bench {
namespace {

/// The smallest binned slip displacement over phi_max: below it one bin holds the density's
/// tail, so the microslip regime is resolved from 1e-4 phi_max up.
constexpr double kFinestSlipRatio = 1e-4;

/// The fundamental and third harmonic of a Jenkins element's force (stiffness k, slip
/// displacement phi) on its steady loop at u = U cos(theta), as complex amplitudes of
/// e^(i theta) and e^(3 i theta), for U > phi (it sticks otherwise). Over the half period from u =
/// U the element sticks, f = k (u - U + phi), until f = -k phi at cos(theta*) = 1 - 2 phi / U, then
/// slides at -k phi; the other half is its mirror, so only odd harmonics (C_n - i S_n with C_n, S_n
/// the cosine and sine coefficients, (2 / pi) times the half period's integrals).
struct JenkinsHarmonics {
    std::complex<double> first;
    std::complex<double> third;
};

JenkinsHarmonics jenkins_harmonics(double k, double phi, double amplitude) {
    const double u = amplitude;
    // cos t = 1 - 2 phi / U; the multiple angles from it (one acos per element, the
    // prediction evaluates this thousands of times per point).
    const double c = 1.0 - 2.0 * phi / u;
    const double t = std::acos(c);
    const double sn = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double sin2 = 2.0 * sn * c, cos2 = 2.0 * c * c - 1.0;
    const double sin4 = 2.0 * sin2 * cos2, cos4 = 2.0 * cos2 * cos2 - 1.0;
    const double sin3 = sn * (3.0 - 4.0 * sn * sn), cos3 = c * (4.0 * c * c - 3.0);
    const double scale = 2.0 / std::numbers::pi;
    // The first harmonic: K' = (k / pi)(t - sin 2t / 2), and the loop's area 4 k phi (U - phi)
    // = pi U^2 K'' gives K'' = (4 k phi / pi U)(1 - phi / U).
    const double c1 = k * u / std::numbers::pi * (t - 0.5 * sin2);
    const double s1 = -4.0 * k * phi / std::numbers::pi * (1.0 - phi / u);
    const double c3 =
        scale * (k * u * (sin2 / 4.0 + sin4 / 8.0) + k * (2.0 * phi - u) * sin3 / 3.0);
    const double s3 = scale * (0.5 * k * u * ((1.0 - cos4) / 4.0 + (1.0 - cos2) / 2.0) +
                               k * (phi - u) * (1.0 - cos3) / 3.0 - k * phi * (1.0 + cos3) / 3.0);
    return {{c1, -s1}, {c3, -s3}};
}

}  // namespace

IwanJoint::IwanJoint(const Eigen::Vector3d& direction, double stiffness_n_per_m,
                     double macroslip_displacement_m, double exponent, int elements,
                     const Eigen::Vector3d& rest_position_m)
    : direction_(direction.normalized()), rest_position_m_(rest_position_m) {
    if (!(stiffness_n_per_m > 0.0) || !(macroslip_displacement_m > 0.0) || !(exponent > -1.0) ||
        elements < 2) {
        throw std::invalid_argument(
            "an Iwan joint needs a positive stiffness and macroslip displacement, an exponent "
            "above -1 and two elements or more");
    }
    const double chi = exponent;
    const double phi_max = macroslip_displacement_m;
    // In units of phi_max: the share of K_T below x is x^(1 + chi), the mean slip displacement
    // of a bin [a, b] is ((1 + chi) / (2 + chi)) (b^(2 + chi) - a^(2 + chi)) /
    // (b^(1 + chi) - a^(1 + chi)).
    const auto share = [chi](double x) { return std::pow(x, 1.0 + chi); };
    const auto moment = [chi](double x) {
        return (1.0 + chi) / (2.0 + chi) * std::pow(x, 2.0 + chi);
    };
    double lower = 0.0;
    for (int i = 0; i < elements; ++i) {
        const double upper =
            std::pow(kFinestSlipRatio, 1.0 - static_cast<double>(i) / (elements - 1));
        const double bin_share = share(upper) - share(lower);
        stiffness_.push_back(stiffness_n_per_m * bin_share);
        slip_.push_back(phi_max * (moment(upper) - moment(lower)) / bin_share);
        lower = upper;
    }
    sliders_.assign(stiffness_.size(), 0.0);
}

PointLoad IwanJoint::step(const PointMotion& motion, double dt_s) {
    // The coupled specimen applies the load at the step's end: the sliders follow the
    // displacement predicted there. From the step's start instead, the softening force lags
    // by a step and adds a damping k dt (10 % of the joint's own at the rigid bench's step).
    const double u =
        direction_.dot(motion.position_m - rest_position_m_ + motion.velocity_m_s * dt_s);
    double force = 0.0;
    for (std::size_t i = 0; i < sliders_.size(); ++i) {
        const double stretch = u - sliders_[i];
        if (stretch > slip_[i]) sliders_[i] = u - slip_[i];
        if (stretch < -slip_[i]) sliders_[i] = u + slip_[i];
        force += stiffness_[i] * sliders_[i];
    }
    return {force * direction_, Eigen::Vector3d::Zero()};
}

AttachmentState IwanJoint::state() const {
    AttachmentState s;
    s.sliders = sliders_;
    return s;
}

void IwanJoint::restore(const AttachmentState& state) {
    if (state.dem || state.describing) {
        throw std::invalid_argument("an Iwan joint was given the state of another model");
    }
    if (!state.sliders) {
        sliders_.assign(stiffness_.size(), 0.0);
        return;
    }
    if (state.sliders->size() != sliders_.size()) {
        throw std::invalid_argument("an Iwan joint of " + std::to_string(sliders_.size()) +
                                    " elements was given " + std::to_string(state.sliders->size()) +
                                    " sliders");
    }
    sliders_ = *state.sliders;
}

DescribingFunction::Value IwanJoint::describing(double acceleration_m_s2,
                                                double frequency_hz) const {
    const double w = 2.0 * std::numbers::pi * frequency_hz;
    const double amplitude = acceleration_m_s2 / (w * w);
    DescribingFunction::Value value;
    value.h2_ratio = 0.0;
    value.h3_ratio = 0.0;
    if (!(amplitude > 0.0)) return value;
    // Element by element, what slip takes from k_i U: a stuck element gives exactly nothing.
    std::complex<double> first = 0.0;
    std::complex<double> third = 0.0;
    for (std::size_t i = 0; i < stiffness_.size(); ++i) {
        if (amplitude <= slip_[i]) continue;
        const JenkinsHarmonics h = jenkins_harmonics(stiffness_[i], slip_[i], amplitude);
        first += stiffness_[i] * amplitude - h.first;
        third -= h.third;
    }
    value.apparent_mass_kg = first / (amplitude * w * w);
    if (std::abs(first) > 0.0) value.h3_ratio = std::abs(third) / std::abs(first);
    return value;
}

}  // namespace sb::bench
