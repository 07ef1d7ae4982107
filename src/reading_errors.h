// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Reading errors: measurement errors that are functions of what the
// instrument reads, found in the residuals and counted whole in the
// colored covariance (colored_covariance.h).
//
// A reading error that follows roll is a function of the roll angle, not of
// time: as the spin decays its harmonics sweep in frequency, and a
// sinusoid of one frequency catches only part of them. Harmonics
// h = 1..kMaxRollOrder of the fitted roll angle are tested as lines of
// phase h phi(t) (an order spectrum, regressors cos h phi, sin h phi)
// against the periodogram around the band each sweeps; aliased twins
// (orders that look alike at a few samples per revolution) are dropped.
// The fitted roll, not the measured one: a roll angle sensed in steps
// hides its own steps' error from its harmonics.
//
// A calibration error (the reading a nonlinear function of the angle) is
// not a line: it follows the channel's own angle, and a fit without it
// absorbs much of it into the coefficients (an error growing as theta^3
// decays three times as fast as the motion: extra damping). The powers 2
// and 3 of pitch and yaw are tested, as the fit leaves them, against the
// rest's own autocorrelation; one that stands out in either channel of a
// segment is fitted in both.
//
// Those found are fitted together over every series, as the fit leaves
// them, K = (I - J B J^T) U: the fit couples the channels (what it absorbs
// of an error in theta shows in psi's residual too), and an error fitted
// to one channel alone would be taken for part of another's echo. Errors
// the fit could absorb whole (kept share below kMinKeptShare) stay in the
// autocorrelation. A line of random phase and amplitude a adds
// (a^2 / 2) Re(c c^H), c = J^T (cos + i sin); a calibration term of unknown
// sign and size a adds a^2 c c^T, c = J^T angle^p: the bias it causes,
// squared.

#ifndef FIT3DOF_SRC_READING_ERRORS_H_
#define FIT3DOF_SRC_READING_ERRORS_H_

#include <Eigen/Core>
#include <vector>

#include "colored_covariance.h"

namespace fit3dof {

// Takes the reading errors of every series out of `rests` (one residual
// per series, initially the series' residuals), appends each to its
// series' `lines`, and returns their share of the bracket; b is
// (J^T J)^-1 of all series together.
Eigen::MatrixXd ReadingErrorBracket(
    const std::vector<ResidualSeries>& series,
    const Eigen::MatrixXd& b,
    std::vector<Eigen::VectorXd>* rests,
    std::vector<std::vector<ResidualLine>>* lines);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_READING_ERRORS_H_
